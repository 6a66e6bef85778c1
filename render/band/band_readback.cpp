#include "render/band/band_readback.h"

#include <algorithm>
#include <cstddef>

#include "core/parallel_for.h"
#include "render/frame/tile_culling.h"

namespace zenith::render {

void pack_band_rows(std::span<const float> rgba, const BandTiles& band, int width, int tile_columns,
                    std::vector<float>& rows_rgb) {
  const int rows = band.rows;
  rows_rgb.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(rows) * 3);
  core::parallel_for(static_cast<std::size_t>(band.tile_rows), 0, [&](std::size_t tile_row) {
    const int y_end = std::min(rows, static_cast<int>(tile_row + 1) * kTileSize);
    for (int y = static_cast<int>(tile_row) * kTileSize; y < y_end; ++y)
      for (int tx = 0; tx < tile_columns; ++tx) {
        const std::size_t begin = static_cast<std::size_t>(y) * width + static_cast<std::size_t>(tx) * kTileSize;
        const std::size_t end = static_cast<std::size_t>(y) * width + std::min(width, (tx + 1) * kTileSize);
        if (band.black[tile_row * static_cast<std::size_t>(tile_columns) + static_cast<std::size_t>(tx)]) {
          std::fill(rows_rgb.begin() + static_cast<std::ptrdiff_t>(3 * begin),
                    rows_rgb.begin() + static_cast<std::ptrdiff_t>(3 * end), 0.0f);
          continue;
        }
        for (std::size_t i = begin; i < end; ++i) {
          rows_rgb[3 * i] = rgba[4 * i];
          rows_rgb[3 * i + 1] = rgba[4 * i + 1];
          rows_rgb[3 * i + 2] = rgba[4 * i + 2];
        }
      }
  });
}

}  // namespace zenith::render
