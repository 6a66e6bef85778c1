#pragma once
// The cluster master (docs/cluster.md): accepts render nodes, authenticates
// them (handshake.h), sends them the lookup tables of every atmosphere of the
// scene, then drives the frame barrier:
//
//   FrameState N ──► every live node ──► RenderDone N from each (or the barrier
//   timeout: late nodes are dropped from the frame with a log line naming them)
//   ──► Present N to every node that finished N ──► FrameState N + 1 …
//
// Nodes join or rejoin at any time; they get the tables, then enter at the
// next frame boundary. All networking runs on one thread (the io_context's);
// the caller's thread only prepares the tables and then runs that loop.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "cluster/cluster_config.h"
#include "cluster/handshake.h"

namespace zenith::cluster {

struct MasterOptions {
  ClusterConfig config;
  std::uint64_t frames = 0;          ///< frames to present, then say Goodbye and return; 0: run until stopped
  double sun_step_deg = 0.1;         ///< the default show: sun turned this much per frame
  std::optional<std::uint16_t> port; ///< overrides config.master.port
  std::optional<std::filesystem::path> cache_directory;  ///< table cache (default: the user's)
  bool cpu_precompute = false;       ///< precompute missing tables on the CPU
  /// Frames start when every configured node is ready, or after this long with
  /// the nodes that are (at least one).
  std::uint32_t wait_for_nodes_ms = 30000;
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
