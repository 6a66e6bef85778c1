#pragma once
// A standby master becoming the master (docs/cluster.md, "Standby master"):
// the table versions it received join the master's table versions, and the
// show continues from the frame after the last one the active master sent,
// its show time going on at the same step. Pure functions: Master::Impl
// (cluster/master/master.cpp) applies them to its barrier, clock and exposure.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cluster/link/takeover_state.h"
#include "cluster/master/table_versions.h"
#include "scene/scene.h"
#include "show/playback_clock.h"

namespace zenith::cluster {

/// How the show goes on after a takeover.
struct Continuation {
  std::uint64_t next_frame = 0;   ///< the frame after the last one the active master sent
  double last_show_time_s = 0.0;  ///< the show time of that last frame
  /// Show seconds per second of playback, from the last step (step × fps): 1
  /// when fewer than two consecutive frames were seen, or the step is no
  /// playback rate (a seek, a loop's wrap: beyond ±16).
  double rate = 1.0;
  bool paused = false;  ///< the last two frames had the same show time
  /// The operator's exposure of the last frame, when it differs from what the show gives.
  std::optional<double> exposure;
  /// What of the last frame this master would not have sent the same way
  /// ("sun direction", "camera position", …): the standby's scene, show or
  /// --sun-step-deg differ from the active master's, and the picture jumps.
  std::vector<std::string> mismatches;
};

/// The continuation of `state`'s last frame (precondition: it has one);
/// `expected` is the state this master's own show gives for that frame's
/// number and show time, `fps` its frames per second.
Continuation continuation_of(const TakeoverState& state, const FrameState& expected, double fps);

/// Sets a show's playback clock so that its next frame is the one after the
/// last frame's, at the continuation's rate (or paused).
void continue_clock(const Continuation& continuation, show::PlaybackClock& clock);

/// continuation_of, with the log lines of a takeover: each mismatch (the
/// picture jumps), and the frame the show goes on at with how many versions.
Continuation continue_show(const TakeoverState& state, const FrameState& expected, double fps);

/// Adds every version of `state` to `tables` (its definition resolved at
/// `scene`'s wavelengths and checked, its set kept for sending); with
/// `default_show`, the last frame's versions become the current ones with the
/// frames they took effect at. Throws std::runtime_error when a definition
/// does not resolve here or the last frame uses a version not received.
void adopt_takeover_tables(const TakeoverState& state, const scene::Scene& scene, TableVersions& tables,
                           bool default_show);

}  // namespace zenith::cluster
