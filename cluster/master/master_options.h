#pragma once
// What a master is asked to do (docs/cluster.md, docs/shows.md,
// docs/operator.md): the cluster configuration and the command line's
// choices, in one value the master's parts read (the frame loop, the
// playback, the table schedule) without knowing the master itself.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "cluster/link/cluster_config.h"
#include "cluster/link/takeover_state.h"
#include "cluster/master/atmosphere_switch.h"
#include "cluster/master/frame_feed.h"
#include "cluster/operator/operator_console_options.h"

namespace zenith::cluster {

struct HouseTimecode;

struct MasterOptions {
  ClusterConfig config;
  std::uint64_t frames = 0;           ///< frames to present, then say Goodbye and return; 0: run until stopped
  double sun_step_deg = 0.1;          ///< the default show: sun turned this much per frame
  std::optional<std::uint16_t> port;  ///< overrides config.master.port
  std::optional<std::filesystem::path> cache_directory;  ///< table cache (default: the user's)
  bool cpu_precompute = false;                           ///< precompute missing tables on the CPU
  /// Frames start when every configured node is ready, or after this long with
  /// the nodes that are (at least one).
  std::uint32_t wait_for_nodes_ms = 30000;
  /// Called once the cluster port (and the console's) are bound, before the
  /// tables are prepared: `zenith cluster` starts its nodes only then
  /// (cluster/launcher/launcher_signals.h).
  std::function<void()> on_listening;
  /// Parameter changes made during the default show (from the command line).
  std::vector<AtmosphereSwitch> atmosphere_switches;

  // ---- shows (docs/shows.md) ----
  /// Plays this show file instead of the default show; its scene replaces the
  /// configuration's. Its table sets are prepared in order of first use while
  /// frames go on; frame 0 waits for its own sets (and, paced, until the rest
  /// are predicted ready in time). Not combined with atmosphere_switches.
  std::optional<std::filesystem::path> show;
  /// Frames per second of show time; 0: the show's own rate for recordings,
  /// the configuration's frame_rate_hz otherwise.
  double show_fps = 0.0;
  std::optional<bool> loop;  ///< overrides the show's "loop"
  /// Pace frames at the frame rate (live). false: as fast as the barrier
  /// allows (offline rendering through the cluster).
  bool paced = true;
  /// Records every presented frame state into this show file (a recording),
  /// written when the master stops.
  std::optional<std::filesystem::path> record;
  /// The house's timecode the show chases (its "timecode" block; docs/shows.md,
  /// "Chasing timecode"): LTC from an ALSA capture device ("hw:1,0") or from
  /// an audio file played in real time (a rehearsal), `ltc_channel` the
  /// channel that carries it; or MIDI timecode from an ALSA raw MIDI port
  /// ("hw:1,0,0"). At most one of the three.
  std::string ltc_device, mtc_device;
  std::optional<std::filesystem::path> ltc_file;
  int ltc_channel = 0;
  /// When `ltc_file`'s first sample sounds, in Unix seconds (unset: the
  /// master's start): masters given the same instant chase one rehearsal.
  std::optional<double> ltc_file_epoch_s;
  /// The input above already open and chased (a standby's, opened while it
  /// followed; set by cluster/standby/standby.h): used instead of opening it again.
  std::shared_ptr<HouseTimecode> house_timecode;
  /// Playback commands from standard input, one per line (docs/shows.md, "Playback").
  bool console = false;
  /// Playback commands on a TCP control socket at 127.0.0.1:PORT (`zenith show control`).
  std::optional<std::uint16_t> control_port;
  /// The operator console: HTTP and OSC (docs/operator.md).
  OperatorConsoleOptions operator_console;
  /// Offline rendering through the cluster: frames come from this feed (the
  /// show still names the table sets to prepare); the master stops when the
  /// feed is finished and empty. Not combined with a show clock's commands.
  std::shared_ptr<FrameFeed> feed;
  /// Test hook (`--debug-table-delay-ms`): every table set prepared in the
  /// background after the first takes this much longer (plays a slow precompute).
  std::uint32_t debug_table_delay_ms = 0;
  /// A standby master taking over (docs/cluster.md, "Standby master"; set by
  /// cluster/standby/standby.h, not on the command line): with a last frame, the
  /// active master's table versions are used instead of prepared (a show's
  /// sets not received are prepared as at the start) and the show continues
  /// from the frame after the last one it sent, at the same show-time step,
  /// as soon as every configured node is ready (or wait_for_nodes_ms passed).
  std::shared_ptr<const TakeoverState> takeover;
};

}  // namespace zenith::cluster
