#pragma once
// What the master plays (docs/shows.md): a show file with its playback clock,
// or the configuration's scene (the default show, its sun turning), at which
// frame rate, and the recorder of `--record`.
#include <cstdint>
#include <memory>
#include <optional>

#include "cluster/master/house_timecode.h"
#include "cluster/master/master_options.h"
#include "scene/scene.h"
#include "show/playback_clock.h"
#include "show/show.h"

namespace zenith::cluster {

struct Playback {
  scene::Scene scene;                            ///< the show's scene, or the configuration's
  std::optional<show::Show> show;                ///< nullopt: the default show
  std::optional<show::PlaybackClock> clock;      ///< a show's
  double fps = 30.0;                             ///< frames per second of show time (and of pacing)
  std::uint32_t render_flags = 0;                ///< every frame's (render::RenderOptions' defaults)
  std::unique_ptr<show::ShowRecorder> recorder;  ///< with MasterOptions::record
  /// Chasing the house's timecode (MasterOptions::ltc_device, ltc_file or
  /// mtc_device): show time from the chase at each frame's moment instead of the clock.
  std::shared_ptr<HouseTimecode> timecode;
  show::ChasePosition chased;  ///< the last frame's, for the status and the log
};

/// Loads what `options` plays into `playback` (logged) and starts its
/// timecode input (or takes MasterOptions::house_timecode's). Throws for a bad show or scene file,
/// std::invalid_argument for atmosphere switches with a show and for timecode without a show that has a "timecode"
/// block, std::runtime_error for an LTC input that cannot be opened.
void load_playback(const MasterOptions& options, Playback& playback);

}  // namespace zenith::cluster
