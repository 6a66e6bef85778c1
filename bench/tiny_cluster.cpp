#include "bench/tiny_cluster.h"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>

namespace zenith::bench {

std::string tiny_node_name(int i) { return fmt::format("n{}", i); }

std::filesystem::path write_tiny_cluster(const std::filesystem::path& dir, const TinyCluster& t) {
  {
    std::ofstream v(dir / "viewports.json");
    v << fmt::format(R"({{"zenith_viewports": 1, "name": "{}", "outputs": [)", t.name);
    const int half = t.size_px / 2;
    for (int i = 0; i < t.nodes; ++i)
      v << (i ? "," : "")
        << fmt::format(R"({{"name": "o{}", "size": [{}, {}], "projection": {{"type": "fisheye", )"
                       R"("fov_deg": 180, "centre_x_px": {}, "centre_y_px": {}, "radius_px": {}}}}})",
                       i, t.size_px, t.size_px, half, half, std::max(half, 1));
    v << "]}\n";
  }
  const std::filesystem::path config = dir / "cluster.json";
  std::ofstream c(config);
  c << fmt::format(R"({{"zenith_cluster": 1, "name": "{}", "master": {{"host": "127.0.0.1", "port": {}}},)", t.name,
                   t.port)
    << fmt::format(R"( "scene": "{}", "viewports": "viewports.json",)",
                   (std::filesystem::path(ZENITH_SOURCE_DIR) / "configs/scenes/earth-sunset.json").string())
    << fmt::format(R"( "timing": {},)", t.timing_json)
    << fmt::format(R"( "secret": {{"env": "{}"}}, "tables": {{"sizes": "{}", "orders": {}}}, "nodes": [)", t.secret_env,
                   t.tables, t.orders);
  for (int i = 0; i < t.nodes; ++i)
    c << (i ? "," : "")
      << fmt::format(R"({{"name": "{}", "host": "127.0.0.1", "outputs": ["o{}"]}})", tiny_node_name(i), i);
  c << R"(], "output": {"directory": "out", "format": "png"}})"
    << "\n";
  return config;
}

}  // namespace zenith::bench
