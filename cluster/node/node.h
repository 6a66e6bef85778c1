#pragma once
// A cluster render node (docs/cluster.md): connects to the master,
// authenticates, receives and caches the lookup tables, then renders every
// FrameState it is sent into its outputs (headless), reports RenderDone and on
// Present renames the frame's files into place:
//
//   <out>/<node>/<output>/frame-000042.png     (written as ….png.partial, renamed on Present)
//   <out>/<node>/presented.log                 one line per presented frame: "frame N state DIGEST tables B=H,...
//   show_time_s T"
//
// When the connection to the master is lost without a Goodbye, the node keeps
// its last presented frame and reconnects (MasterLink), then rejoins at a
// frame boundary with its cached tables; it exits when the reconnect time runs
// out (kNodeExitMasterLost).
//
// Two threads: the networking thread runs the Boost.Asio io_context (all
// socket work, heartbeats, table reassembly); the caller's thread owns the GL
// context and the renderer. They talk through a job queue (network → render)
// and asio::post (render → network), nothing else is shared.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cluster/link/cluster_config.h"
#include "cluster/link/link_exit.h"
#include "cluster/link/local_clock.h"
#include "cluster/protocol/handshake.h"

namespace zenith::cluster {

/// Where a node writes its frames.
enum class FrameFileLayout {
  per_node,  ///< <out>/<node>/<output>/frame-NNNNNN.ext (live shows)
  offline,   ///< <out>/<output>/<output>.NNNNNN.ext, logs in <out>/nodes/<node>/ (`zenith show render --cluster`)
};

struct NodeOptions {
  ClusterConfig config;
  std::string node_name;                     ///< one of config.nodes
  std::filesystem::path output_directory;    ///< frames go to <this>/<node>/<output>/
  std::filesystem::path cache_directory;     ///< the node's own table cache
  std::optional<std::uint16_t> port;         ///< overrides config.master.port
  std::uint32_t connect_timeout_ms = 15000;  ///< keep trying to reach the master this long
  /// After losing a welcomed connection, keep trying to be welcomed again
  /// this long (`--reconnect-s`); unset: the configuration's timing.reconnect_s.
  std::optional<std::uint32_t> reconnect_ms;
  /// Atmosphere files (besides the scene's atmospheres and the built-in
  /// presets) whose tables the master may switch to during the show: a node
  /// can only use a table version whose parameters it knows (docs/cluster.md).
  std::vector<std::filesystem::path> atmosphere_files;
  /// Renders this scene instead of the configuration's (a show's scene:
  /// `zenith cluster --show` passes it to master and nodes alike).
  std::optional<std::filesystem::path> scene;
  FrameFileLayout layout = FrameFileLayout::per_node;
  /// Write the frame files (and thumbnails' sources stay on the GPU either
  /// way). A live show writes none unless asked (`zenith node --out DIR` or
  /// `--record-frames DIR`); an offline render (layout offline) always does.
  /// presented.log is written either way.
  bool write_frames = true;
  /// Show each presented frame on the node's displays (GLFW; needs a
  /// display): every output in the window its viewport config gives it
  /// ("window": warp/output_window.h), the others side by side in one
  /// decorated window, as a projector shows them (tone mapped, blended,
  /// encoded: render/display/display_encoder.h). Closing a window or Escape
  /// leaves the cluster.
  bool window = false;
  /// Test hook (`--debug-render-delay-ms`): sleep this long before each frame,
  /// to play a slow node. 0 in production.
  std::uint32_t debug_render_delay_ms = 0;
  /// Rehearsal of a PC whose clock misbehaves (`--debug-clock-drift-ppm`,
  /// `--debug-clock-step-ms`, `--debug-clock-step-every-s`): the node's clock,
  /// as its clock synchronisation reads it, drifts and steps this way from the
  /// node's start (cluster/link/local_clock.h); the machine's time is never
  /// touched. None in production.
  LocalClock::Faults debug_clock_faults;
};

class Node {
 public:
  Node(NodeOptions options, SharedSecret secret);
  ~Node();
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  /// Runs until the master says Goodbye, a signal, a failure, or the reconnect
  /// time runs out after a lost connection; returns a NodeExit code.
  int run();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace zenith::cluster
