#pragma once
// A local cluster of tiny outputs for the cluster benchmark and the soak
// (bench/cluster_bench.cpp, bench/cluster_soak.cpp): N fisheye outputs of
// PX×PX ("o0", "o1", …), node "n<i>" rendering output "o<i>", the
// earth-sunset scene, all nodes on 127.0.0.1.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "bench/command_line.h"

namespace zenith::bench {

/// The options every run of a tiny cluster takes (cluster_bench, cluster_soak);
/// each program's Options derive from it and set the defaults that differ.
struct TinyRunOptions {
  std::filesystem::path zenith;                ///< --zenith: the zenith binary
  int size_px = 16;                            ///< --size PX: each output is PX×PX
  std::optional<std::filesystem::path> cache;  ///< --cache DIR: the table cache
  std::filesystem::path work;                  ///< --work DIR: the run folder
  int timeout_s = 600;                         ///< --timeout-s S: give up after this long
  bool keep = false;                           ///< --keep: keep the run folders

  /// Reads the current option of `args` when it is one of the above; --help
  /// (-h) prints `usage` and exits. True when the option was one of these.
  bool read(CommandLine& args, const char* usage) {
    const std::string& a = args.option();
    if (a == "--help" || a == "-h") {
      std::fputs(usage, stdout);
      std::exit(0);
    }
    if (a == "--zenith")
      zenith = args.value();
    else if (a == "--size")
      size_px = std::stoi(args.value());
    else if (a == "--cache")
      cache = std::filesystem::path(args.value());
    else if (a == "--work")
      work = args.value();
    else if (a == "--timeout-s")
      timeout_s = std::stoi(args.value());
    else if (a == "--keep")
      keep = true;
    else
      return false;
    return true;
  }
};

struct TinyCluster {
  std::string name;  ///< the cluster's name
  int nodes = 1;
  int size_px = 16;
  int port = 0;                  ///< the master's, on 127.0.0.1
  std::string timing_json;       ///< the "timing" object, e.g. {"heartbeat_ms": 250, …}
  std::string secret_env;        ///< the variable holding the shared secret
  std::string tables = "small";  ///< table sizes
  int orders = 1;                ///< scattering orders
};

/// "n<i>": the name of node i.
std::string tiny_node_name(int i);

/// Writes `dir`/viewports.json and `dir`/cluster.json (frames to "out", PNG); returns the cluster file.
std::filesystem::path write_tiny_cluster(const std::filesystem::path& dir, const TinyCluster& cluster);

}  // namespace zenith::bench
