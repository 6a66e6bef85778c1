#pragma once
// A node's thumbnail of one output for the operator console's dome preview
// (docs/protocol.md, "PreviewRequest (19), Thumbnail (20)"): the output as
// its projector shows it (display-linear: tone mapped, blended), box-filtered
// down to at most edge_px on its longer side, 8-bit sRGB. Made only for a
// frame the master asked thumbnails of.
#include <cstdint>
#include <span>
#include <string>

#include "cluster/protocol/messages.h"
#include "render/display/display_encoder.h"

namespace zenith::cluster {

/// The thumbnail of a `width_px` × `height_px` output `output` of `frame`:
/// `display_rgb` its display-linear values (width · height · 3, [0, 1]; outside
/// is clamped). The longer side becomes min(edge_px, its length), the other
/// keeps the aspect ratio (rounded, at least 1 pixel); each thumbnail pixel
/// is the mean of the output pixels it covers (NaN as 0), then sRGB encoded and rounded.
/// Throws std::invalid_argument for sizes below 1, edge_px outside
/// [1, kMaxThumbnailEdgePx] or a value count other than width · height · 3.
Thumbnail make_thumbnail(std::uint64_t frame, const std::string& output, std::span<const float> display_rgb,
                         int width_px, int height_px, int edge_px);
/// The thumbnail of box means the GPU reduced (render::display::DisplayEncoder::thumbnail):
/// each mean sRGB encoded and rounded, as above.
Thumbnail make_thumbnail(std::uint64_t frame, const std::string& output, const render::display::ThumbnailMeans& means);

}  // namespace zenith::cluster
