#pragma once
// How far two frames are apart on the display (the star tests: a frame where
// the stars' test skipped them against the same frame with them forced on).
// The test's bound is on the continuous code value 255 E(T(x))
// (render/night/star_visibility.h): where it skips, every value moves by less
// than half a code, so each 8-bit code is the same — or one step away where the
// sky sits within that change of a rounding boundary.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "image/colour.h"
#include "image/tone_mapping.h"

namespace zenith::render::testing {

/// The continuous 8-bit code value of exposed radiance x: 255 E(T(x)).
inline double code_value(float x, image::ToneMapping tone) {
  return 255.0 * static_cast<double>(image::srgb_encode(image::tone_map(x, tone)));
}

/// The largest change of a continuous code value, the count of 8-bit codes
/// that differ and the largest step between them, over both tone operators.
struct CodeDifference {
  double largest_code_change = 0.0;
  std::size_t codes_differing = 0;
  int largest_byte_change = 0;
};

inline CodeDifference code_difference(const std::vector<float>& a, const std::vector<float>& b) {
  CodeDifference d;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (image::ToneMapping tone : {image::ToneMapping::exponential, image::ToneMapping::clamp}) {
      d.largest_code_change =
          std::max(d.largest_code_change, std::abs(code_value(a[i], tone) - code_value(b[i], tone)));
      const int step = std::abs(int(image::display_byte(a[i], tone)) - int(image::display_byte(b[i], tone)));
      d.codes_differing += step != 0;
      d.largest_byte_change = std::max(d.largest_byte_change, step);
    }
  return d;
}

}  // namespace zenith::render::testing
