#include "cluster/launcher/dome_stitch.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "image/image_writer.h"
#include "warp/dome_tiles.h"
#include "warp/viewport_config.h"

namespace zenith::app {

namespace fs = std::filesystem;

std::optional<StitchedDome> stitch_dome(const cluster::ClusterConfig& config, const fs::path& out, std::uint64_t frame,
                                        const fs::path& target) {
  const warp::ViewportConfig viewports = warp::load_viewport_config(config.viewports);
  struct Tile {
    const warp::OutputConfig* output;
    std::string node;
  };
  std::vector<Tile> tiles;
  std::vector<const warp::OutputConfig*> outputs;
  for (const auto& node : config.nodes)
    for (const std::string& name : node.outputs) {
      tiles.push_back({viewports.find(name), node.name});
      outputs.push_back(tiles.back().output);
    }
  const auto origins = warp::dome_tile_origins(outputs);
  if (!origins) {
    spdlog::info("cluster: not stitching: the outputs are not whole-pixel tiles of one fisheye dome master");
    return std::nullopt;
  }
  int width = 0, height = 0;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    width = std::max(width, (*origins)[i][0] + tiles[i].output->width_px);
    height = std::max(height, (*origins)[i][1] + tiles[i].output->height_px);
  }
  std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3, 0.0f);
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const Tile& t = tiles[i];
    const fs::path file = out / t.node / t.output->name / fmt::format("frame-{:06d}.png", frame);
    if (!fs::exists(file)) {
      spdlog::warn("cluster: not stitching frame {}: {} is missing", frame, file.string());
      return std::nullopt;
    }
    const image::LinearImage tile = image::read_image(file);
    const int x0 = (*origins)[i][0], y0 = (*origins)[i][1];
    for (int y = 0; y < tile.height; ++y)
      for (int x = 0; x < tile.width; ++x)
        for (int c = 0; c < 3; ++c)
          rgb[(static_cast<std::size_t>(y0 + y) * width + (x0 + x)) * 3 + c] =
              tile.rgb[(static_cast<std::size_t>(y) * tile.width + x) * 3 + c];
  }
  fs::create_directories(target.parent_path());
  // The tiles are decoded sRGB; clamp re-encodes each value to its own byte.
  image::write_png(target, width, height, rgb, image::ToneMapping::clamp,
                   {{"zenith:stitched", fmt::format("frame {} of cluster '{}'", frame, config.name)}});
  return StitchedDome{width, height, tiles.size()};
}

}  // namespace zenith::app
