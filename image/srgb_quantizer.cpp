#include "image/srgb_quantizer.h"

#include <bit>
#include <cmath>

#include "image/tone_mapping.h"

namespace zenith::image {
namespace {

/// The reference: round(255 · srgb_encode(t)), as display_byte computes it.
int code_of(float linear) { return static_cast<int>(std::lround(255.0f * srgb_encode(linear))); }

}  // namespace

SrgbQuantizer::SrgbQuantizer() {
  // For non-negative floats, the IEEE-754 bit patterns read as unsigned integers
  // are ordered like the values, so bisection over [bits(0), bits(1)] finds the
  // first float of each step in 30 evaluations. code(0) = 0 < k ≤ 255 = code(1).
  const std::uint32_t zero_bits = std::bit_cast<std::uint32_t>(0.0f);
  const std::uint32_t one_bits = std::bit_cast<std::uint32_t>(1.0f);
  step_[0] = 0.0f;
  for (int k = 1; k <= 255; ++k) {
    std::uint32_t below = zero_bits, at_or_above = one_bits;  // code(below) < k ≤ code(at_or_above)
    while (at_or_above - below > 1) {
      const std::uint32_t mid = below + (at_or_above - below) / 2;
      if (code_of(std::bit_cast<float>(mid)) >= k)
        at_or_above = mid;
      else
        below = mid;
    }
    step_[k] = std::bit_cast<float>(at_or_above);
  }
  step_[256] = std::numeric_limits<float>::infinity();
  int code = 0;
  for (int i = 0; i < kBuckets; ++i) {
    const float t = float(i) / float(kBuckets);
    while (t >= step_[code + 1]) ++code;
    bucket_code_[i] = static_cast<std::uint8_t>(code);
  }
}

}  // namespace zenith::image
