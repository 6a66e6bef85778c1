// A band read back to the CPU (render/band/band_readback.h): the RGB of each
// pixel's (r, g, b, 0), and zeros for the black tiles whose memory holds an
// earlier band's values. No GL context: the output buffer as a plain vector.
#include "render/band/band_readback.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "render/frame/tile_culling.h"

namespace zenith::render {
namespace {

TEST(BandReadback, PacksRgbAndZeroesBlackTilesOfAPartialBand) {
  // 40 × 20 pixels: 3 tile columns (the last 8 pixels wide), 2 tile rows (the last 4 rows high).
  const int width = 40, columns = 3;
  BandTiles band;
  band.first_row = 32;
  band.rows = 20;
  band.tile_rows = 2;
  band.black = {0, 1, 0,  //
                1, 0, 1};
  std::vector<float> rgba(static_cast<std::size_t>(width) * 20 * 4);
  for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = static_cast<float>(i) + 0.5f;
  std::vector<float> rows_rgb(7, -1.0f);  // resized, and every value written

  pack_band_rows(rgba, band, width, columns, rows_rgb);

  ASSERT_EQ(rows_rgb.size(), static_cast<std::size_t>(width) * 20 * 3);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t tile =
          static_cast<std::size_t>(y / kTileSize) * columns + static_cast<std::size_t>(x / kTileSize);
      const std::size_t i = static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x);
      for (std::size_t c = 0; c < 3; ++c) {
        const float expected = band.black[tile] ? 0.0f : rgba[4 * i + c];
        ASSERT_EQ(rows_rgb[3 * i + c], expected) << "pixel (" << x << ", " << y << ") channel " << c;
      }
    }
}

TEST(BandReadback, ReadsNoMemoryOfABandWhoseTilesAreAllBlack) {
  const int width = 16;
  BandTiles band;
  band.rows = 16;
  band.tile_rows = 1;
  band.black = {1};
  std::vector<float> rows_rgb;
  pack_band_rows({}, band, width, 1, rows_rgb);  // an empty buffer: nothing of it may be read
  ASSERT_EQ(rows_rgb.size(), 16u * 16u * 3u);
  for (const float v : rows_rgb) ASSERT_EQ(v, 0.0f);
}

}  // namespace
}  // namespace zenith::render
