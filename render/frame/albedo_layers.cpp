#include "render/frame/albedo_layers.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace zenith::render {

AlbedoLayers resample_albedo_layers(const std::vector<const image::LinearImage*>& maps) {
  int width = 1, height = 1;
  for (const image::LinearImage* m : maps) {
    width = std::max(width, m->width);
    height = std::max(height, m->height);
  }
  const std::size_t layer_floats = static_cast<std::size_t>(width) * height * 4;
  std::vector<float> rgba(std::max<std::size_t>(maps.size(), 1) * layer_floats, 1.0f);
  for (std::size_t layer = 0; layer < maps.size(); ++layer) {
    const image::LinearImage& m = *maps[layer];
    float* const first = &rgba[layer * layer_floats];
    if (m.width == 1 && m.height == 1) {  // a constant albedo: its colour everywhere
      for (std::size_t t = 0; t < layer_floats; t += 4) std::copy_n(m.rgb.data(), 3, first + t);
      continue;
    }
    if (m.width == width && m.height == height) {  // at the array's size: texel for texel
      for (std::size_t t = 0, n = static_cast<std::size_t>(width) * height; t < n; ++t)
        std::copy_n(&m.rgb[3 * t], 3, first + 4 * t);
      continue;
    }
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        // Texel centres map to texel centres; x wraps (longitude), y clamps (poles).
        const double sx = (x + 0.5) * m.width / width - 0.5, sy = (y + 0.5) * m.height / height - 0.5;
        const double fx = std::floor(sx), fy = std::floor(sy);
        const double tx = sx - fx, ty = sy - fy;
        auto at = [&](int xi, int yi, int k) {
          xi = ((xi % m.width) + m.width) % m.width;
          yi = std::clamp(yi, 0, m.height - 1);
          return static_cast<double>(m.rgb[(static_cast<std::size_t>(yi) * m.width + xi) * 3 + k]);
        };
        const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
        float* out = &rgba[layer * layer_floats + (static_cast<std::size_t>(y) * width + x) * 4];
        for (int k = 0; k < 3; ++k)
          out[k] = static_cast<float>((1 - ty) * ((1 - tx) * at(x0, y0, k) + tx * at(x0 + 1, y0, k)) +
                                      ty * ((1 - tx) * at(x0, y0 + 1, k) + tx * at(x0 + 1, y0 + 1, k)));
      }
  }
  AlbedoLayers out;
  out.width = width;
  out.height = height;
  out.layers = std::max<std::size_t>(maps.size(), 1);
  out.rgba = std::move(rgba);
  return out;
}

}  // namespace zenith::render
