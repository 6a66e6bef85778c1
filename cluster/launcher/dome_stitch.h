#pragma once
// One dome master from its tiles (docs/cluster.md, "A local cluster"): the
// outputs of a cluster that cut one fisheye image circle into whole-pixel
// tiles (warp/dome_tiles.h), each written by its node as
// OUT/<node>/<output>/frame-N.png, pasted back into one PNG.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>

#include "cluster/link/cluster_config.h"

namespace zenith::app {

struct StitchedDome {
  int width_px = 0, height_px = 0;
  std::size_t tiles = 0;
};

/// Stitches frame `frame` of the configuration's outputs under `out` into
/// `target`; nothing (with a log line) when the outputs are not tiles of one
/// dome master or a tile's file is missing.
std::optional<StitchedDome> stitch_dome(const cluster::ClusterConfig& config, const std::filesystem::path& out,
                                        std::uint64_t frame, const std::filesystem::path& target);

}  // namespace zenith::app
