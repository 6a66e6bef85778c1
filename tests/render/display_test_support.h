#pragma once
// Helpers of the display-pass tests (colour_profile_gpu_test.cpp,
// mpcdi_maps_gpu_test.cpp): a frame through the GPU's display pass, read back
// as codes, and the comparison of two frames' codes.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>

#include "render/display/display_encoder.h"
#include "tests/render/render_test_support.h"

namespace zenith::render::testing {

/// The codes (R, G, B of every pixel, row 0 at the top) the display pass
/// writes for `radiance` (rgba floats, width × height) through `stage` into an
/// rgba8 or rgba16 texture of `format`, read back (as only a test does).
inline std::vector<int> display_codes(const std::vector<float>& radiance, int width, int height,
                                      const display::OutputStage& stage, gl::TextureFormat format) {
  context();
  const gl::Texture frame = gl::Texture::create_2d(gl::TextureFormat::rgba32f, width, height, radiance);
  gl::Texture target = gl::Texture::create_2d(format, width, height);
  display::DisplayEncoder encoder;
  encoder.encode(frame, stage, target);
  const std::vector<float> out = target.read();
  const double top = format == gl::TextureFormat::rgba8 ? 255.0 : 65535.0;
  std::vector<int> codes;
  for (std::size_t i = 0; i < out.size(); ++i)
    if (i % 4 != 3) codes.push_back(static_cast<int>(std::lround(out[i] * top)));
  return codes;
}

/// The largest |a[i] − b[i]| of two frames' codes (of the same size).
inline int worst_code_difference(const std::vector<int>& a, const std::vector<int>& b) {
  EXPECT_EQ(a.size(), b.size());
  int worst = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

}  // namespace zenith::render::testing
