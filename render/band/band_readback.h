#pragma once
// A band read back to the CPU: the output buffer holds one (r, g, b, 0) per
// pixel, rows of the frame's width (frame_rgb.glsl); the caller's rows want
// three floats per pixel. The pixels of black tiles were never written (they
// hold an earlier band's values) and read as zero.
#include <span>
#include <vector>

#include "render/frame/tile_classification.h"

namespace zenith::render {

/// `band`'s rows as RGB floats into `rows_rgb` (resized to width · rows · 3)
/// from `rgba` (the output buffer mapped: width · rows · 4 floats), zeros for
/// its black tiles, whose memory is not read; `tile_columns` tiles a row. Both
/// cores, a tile row per task.
void pack_band_rows(std::span<const float> rgba, const BandTiles& band, int width, int tile_columns,
                    std::vector<float>& rows_rgb);

}  // namespace zenith::render
