#pragma once
// An output's warp as a map for hardware that warps itself (projector warp
// engines, media servers): for each node of a regular grid over the projector's
// image, the point (u, v) of the source image the projector shows there, in
// zenith's convention (normalized, (0, 0) at the top-left, v down, absolute).
// docs/warp-meshes.md, "Exporting to warp engines and media servers".
//
// The grid has (2W + 1) × (2H + 1) nodes for a W × H px output, spanning the
// image edge to edge as every warp map zenith reads does (WarpMesh, PFM, MPCDI):
// node (i, j) sits at the projector pixel position (x, y) = (i / 2, j / 2), so
// the odd nodes are the pixel centres and the even ones the pixel corners.
// Whatever a reader interpolates between nodes, at a pixel centre it finds the
// node itself: the rays of every pixel are the renderer's, up to the binary32
// rounding of (u, v) (≤ 6e-8 · the source's field of view).
//
//  * An output with a warp: (u, v) = WarpMesh::sample(x / W, y / H), the value
//    the renderer uses; no data where the mesh has none.
//  * An output without a warp: the identity, (u, v) = (x / W, y / H), the
//    source being the output's own projection at the output's size.
//  * A corner or edge node where the mesh has no data but a neighbouring pixel
//    centre has: the mean (u, v) of those pixel centres (at most half a pixel
//    away), so that every cell around a pixel centre with data has four valid
//    corners and the pixel keeps its ray. Pixel centres without data stay NaN.
#include "warp/pfm.h"
#include "warp/viewport_config.h"

namespace zenith::warp {

struct ExportedWarpMap {
  /// 3 channels (u, v, 0) per node, row 0 at the top; NaN u, v = no data.
  PfmImage map;
  /// The source image the (u, v) address (the output's "projection" renders
  /// it): the warp's source size, or the output's size without a warp.
  int source_width_px = 0, source_height_px = 0;
};

/// The largest output side a map can be exported for: 2 · side + 1 nodes must
/// fit a PFM (kMaxPfmSizePx).
inline constexpr int kMaxExportedWarpSidePx = (kMaxPfmSizePx - 1) / 2;

/// The map above for `output`. Throws std::invalid_argument naming the output
/// for an output without a projection (a broken warp) or wider or taller than
/// kMaxExportedWarpSidePx.
ExportedWarpMap export_warp_map(const OutputConfig& output);

}  // namespace zenith::warp
