#pragma once
// The cluster master (docs/cluster.md): accepts render nodes, authenticates
// them (handshake.h), sends them the lookup tables of every atmosphere of the
// scene, then drives the frame barrier:
//
//   FrameState N ──► every live node ──► RenderDone N from each (or the barrier
//   timeout: late nodes are dropped from the frame with a log line naming them)
//   ──► Present N to every node that finished N ──► FrameState N + 1 …
//
// Nodes join or rejoin at any time; they get the tables (only those their
// cache lacks: the inventory), then enter at the next frame boundary. All
// networking runs on one thread (the io_context's); the caller's thread
// prepares the scene's tables and then runs that loop. Table sets prepared
// while frames go on — a show's later sets, a new version of an atmosphere
// (AtmosphereSwitch) — are obtained in order on one worker thread
// (table_preparer.h) and sent to every node as they are ready (table_schedule.h). A show
// starts once the sets of its first frame are ready (live: once the rest are
// predicted ready in time, show_start_rule.h); a frame whose set is not
// yet held by every node waits for it. A switch takes effect at one frame on
// all nodes once every ready node holds it (docs/cluster.md, "Table versions").
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cluster/link/cluster_config.h"
#include "cluster/link/takeover_state.h"
#include "cluster/master/atmosphere_switch.h"
#include "cluster/master/frame_feed.h"
#include "cluster/master/operator_console_options.h"
#include "cluster/protocol/handshake.h"

namespace zenith::cluster {

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

class Master {
 public:
  Master(MasterOptions options, SharedSecret secret);
  ~Master();
  Master(const Master&) = delete;
  Master& operator=(const Master&) = delete;

  /// Prepares the tables, listens and runs the show. Returns 0 when the frames
  /// were presented (or on SIGINT/SIGTERM, after Goodbye to every node).
  /// Throws for configuration, table or socket errors (port in use).
  int run();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace zenith::cluster
