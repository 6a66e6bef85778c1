#pragma once
// A local cluster (`zenith cluster`, docs/cluster.md "A local cluster"): the
// master, the standby master and every node the configuration places on this
// machine, each a `zenith` child process. The master starts first; the
// others only once it listens (so none joins another cluster's master that
// holds the port). SIGINT, SIGTERM and SIGHUP go to the master, whose Goodbye
// ends the rest; a master killed outright hands over to the local standby; a
// node that dies is restarted within a limit when asked; nodes that all end
// before the master stop it. At the end the last frame's tiles are stitched
// into one dome master when the outputs are tiles of one.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cluster/link/cluster_config.h"

namespace zenith::app {

struct LocalClusterOptions {
  std::filesystem::path config_path;  ///< passed to every child as --cluster
  cluster::ClusterConfig config;      ///< loaded from config_path
  std::optional<int> port;            ///< overrides the configuration's master port
  /// The master's own options after `zenith master --cluster …` (frames, the
  /// show, the console, switches, its cache); the standby gets the same but
  /// --record (one recording: the active master's).
  std::vector<std::string> master_options;
  std::optional<std::filesystem::path> scene;  ///< nodes render this scene (a show's) instead of the config's
  /// Nodes write every presented frame under this directory (--out); none without it.
  std::optional<std::filesystem::path> frame_directory;
  /// With frame files in PNG: this frame is stitched into
  /// frame_directory/stitched/ once the cluster stopped.
  std::optional<std::uint64_t> stitch_frame;
  std::optional<std::filesystem::path> cache_directory;  ///< nodes use CACHE/nodes/<node>
  bool windows = false;                                  ///< nodes show their frames in windows
  bool restart_nodes = false;                            ///< a local node (or the standby) that dies is restarted …
  std::uint32_t max_restarts = 5;                        ///< … at most this often
  double restart_window_s = 60.0;                        ///< … within this many seconds
};

/// Runs the local cluster until the master ends. Prints the stitched frame's
/// line on standard output. Throws std::runtime_error when the master could
/// not start or failed, a signal stopped it, the nodes ended before it, or a
/// node failed (after the stitching).
void run_local_cluster(const LocalClusterOptions& options);

}  // namespace zenith::app
