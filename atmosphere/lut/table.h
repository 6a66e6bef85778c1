#pragma once
// Float tables with several channels (one per working wavelength) and the
// same filtering a GL texture with GL_LINEAR and GL_CLAMP_TO_EDGE applies, so
// the CPU and GPU paths read tables identically. Texel i covers
// [i/n, (i+1)/n] and its centre is at (i + ½)/n.
#include <cstddef>
#include <vector>

namespace zenith::atmosphere::lut {

/// Most working wavelengths a parameter set may have (docs/atmosphere-config.md).
inline constexpr std::size_t kMaxChannels = 64;

struct Table2D {
  std::size_t width = 0, height = 0, channels = 0;
  std::vector<float> data;  ///< [y][x][channel]

  Table2D() = default;
  Table2D(std::size_t w, std::size_t h, std::size_t c) : width(w), height(h), channels(c), data(w * h * c, 0.0f) {}
  float* texel(std::size_t x, std::size_t y) { return &data[(y * width + x) * channels]; }
  const float* texel(std::size_t x, std::size_t y) const { return &data[(y * width + x) * channels]; }
  /// Bilinear sample at texture coordinates (u, v) ∈ [0, 1]² into out[0..channels).
  void sample(double u, double v, double* out) const;
};

struct Table3D {
  std::size_t width = 0, height = 0, depth = 0, channels = 0;
  std::vector<float> data;  ///< [z][y][x][channel]

  Table3D() = default;
  Table3D(std::size_t w, std::size_t h, std::size_t d, std::size_t c)
      : width(w), height(h), depth(d), channels(c), data(w * h * d * c, 0.0f) {}
  float* texel(std::size_t x, std::size_t y, std::size_t z) { return &data[((z * height + y) * width + x) * channels]; }
  const float* texel(std::size_t x, std::size_t y, std::size_t z) const {
    return &data[((z * height + y) * width + x) * channels];
  }
  /// Trilinear sample at texture coordinates (u, v, w) ∈ [0, 1]³ into out[0..channels).
  void sample(double u, double v, double w, double* out) const;
};

}  // namespace zenith::atmosphere::lut
