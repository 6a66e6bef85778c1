#pragma once
// A local cluster of tiny outputs for the cluster benchmark and the soak
// (bench/cluster_bench.cpp, bench/cluster_soak.cpp): N fisheye outputs of
// PX×PX ("o0", "o1", …), node "n<i>" rendering output "o<i>", the
// earth-sunset scene, all nodes on 127.0.0.1.
#include <filesystem>
#include <string>

namespace zenith::bench {

struct TinyCluster {
  std::string name;                  ///< the cluster's name
  int nodes = 1;
  int size_px = 16;
  int port = 0;                      ///< the master's, on 127.0.0.1
  std::string timing_json;           ///< the "timing" object, e.g. {"heartbeat_ms": 250, …}
  std::string secret_env;            ///< the variable holding the shared secret
  std::string tables = "small";      ///< table sizes
  int orders = 1;                    ///< scattering orders
};

/// "n<i>": the name of node i.
std::string tiny_node_name(int i);

/// Writes `dir`/viewports.json and `dir`/cluster.json (frames to "out", PNG); returns the cluster file.
std::filesystem::path write_tiny_cluster(const std::filesystem::path& dir, const TinyCluster& cluster);

}  // namespace zenith::bench
