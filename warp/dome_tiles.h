#pragma once
// Tiles of one dome master: fisheye outputs that share one image circle (the
// same radius in pixels) with their centres moved, so each renders a
// rectangle of the same picture (configs/viewports/dome-quadrants.json). Where
// each tile sits in that picture lets the outputs be put back together — the
// stitched frame of `zenith cluster`, the contact sheet of `zenith show render`.
#include <array>
#include <optional>
#include <vector>

#include "warp/viewport_config.h"

namespace zenith::warp {

/// The top-left corner, in pixels of the whole picture, of each output (in
/// the given order): (max cx − cx, max cy − cy) over the outputs' centres.
/// nullopt unless every output is an angular fisheye of one radius at a
/// whole-pixel offset.
std::optional<std::vector<std::array<int, 2>>> dome_tile_origins(const std::vector<const OutputConfig*>& outputs);

}  // namespace zenith::warp
