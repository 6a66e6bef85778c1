#include "warp/mpcdi_blend.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "core/strings.h"

namespace zenith::warp {

std::vector<float> sample_mpcdi_blend_map(const MpcdiBlendMap& map, int width_px, int height_px) {
  const int w = map.image.width, h = map.image.height;
  if (width_px < 1 || height_px < 1 || w < 1 || h < 1)
    throw std::invalid_argument(core::cat("sample_mpcdi_blend_map: a ", w, "x", h, " map on a ", width_px, "x",
                                          height_px, " output: sizes must be >= 1"));
  // The samples in linear light, once each.
  std::vector<double> linear(static_cast<std::size_t>(w) * h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) linear[static_cast<std::size_t>(j) * w + i] = map.linear(i, j);
  const auto at = [&](int i, int j) { return linear[static_cast<std::size_t>(j) * w + i]; };
  // Per column and per row: the left (top) sample and the weight of the next.
  const auto axis = [](int n_px, int samples, std::vector<int>& index, std::vector<double>& weight) {
    index.resize(static_cast<std::size_t>(n_px));
    weight.resize(static_cast<std::size_t>(n_px));
    for (int x = 0; x < n_px; ++x) {
      const double s = std::clamp((x + 0.5) / n_px * samples - 0.5, 0.0, static_cast<double>(samples - 1));
      const int i = std::min(static_cast<int>(std::floor(s)), std::max(samples - 2, 0));
      index[static_cast<std::size_t>(x)] = i;
      weight[static_cast<std::size_t>(x)] = samples > 1 ? s - i : 0.0;
    }
  };
  std::vector<int> column, row;
  std::vector<double> column_weight, row_weight;
  axis(width_px, w, column, column_weight);
  axis(height_px, h, row, row_weight);
  std::vector<float> values(static_cast<std::size_t>(width_px) * height_px);
  for (int y = 0; y < height_px; ++y) {
    const int j = row[static_cast<std::size_t>(y)], j1 = std::min(j + 1, h - 1);
    const double ft = row_weight[static_cast<std::size_t>(y)];
    for (int x = 0; x < width_px; ++x) {
      const int i = column[static_cast<std::size_t>(x)], i1 = std::min(i + 1, w - 1);
      const double fs = column_weight[static_cast<std::size_t>(x)];
      // a + f · (b − a): exact where neighbouring samples are equal (a constant map stays constant).
      const double top = at(i, j) + fs * (at(i1, j) - at(i, j));
      const double bottom = at(i, j1) + fs * (at(i1, j1) - at(i, j1));
      values[static_cast<std::size_t>(y) * width_px + x] = static_cast<float>(top + ft * (bottom - top));
    }
  }
  return values;
}

void check_grey_blend_map(const MpcdiBlendMap& map, const std::string& source, const std::string& region_id,
                          const char* what) {
  if (map.image.channels == 1) return;
  for (int y = 0; y < map.image.height; ++y)
    for (int x = 0; x < map.image.width; ++x) {
      const float r = map.image.at(x, y, 0), g = map.image.at(x, y, 1), b = map.image.at(x, y, 2);
      if (r == g && g == b) continue;
      throw std::runtime_error(core::cat(
          source, ":", map.line, ": region '", region_id, "': ", what, " '", map.path,
          "' is RGB with channels that "
          "differ (pixel (",
          x, ", ", y, "): ", r, ", ", g, ", ", b,
          "): per-channel alpha and beta (colour levels 4 "
          "and 5) are not applied by zenith's output stage, which takes one value a pixel; write the map grey, or "
          "set the output's \"blend\" to another type (docs/warp-meshes.md, \"Alpha and beta maps\")"));
    }
}

}  // namespace zenith::warp
