#pragma once
// Private to zenith_image: a fast, exact replacement for
// round(255 · srgb_encode(t)) used by the PNG writer on every pixel.
#include <array>
#include <cstdint>
#include <limits>

namespace zenith::image {

/// Maps a linear value t to the 8-bit sRGB code round(255 · srgb_encode(t))
/// (tone_mapping.h) without evaluating pow. The code is a non-decreasing step
/// function of t, so it is fixed by the 255 values where it steps up. Each is
/// found once, exactly, by bisection over the bit patterns of the non-negative
/// floats (which order like the floats themselves) with srgb_encode itself as
/// the oracle; the result therefore equals the formula for every float, bit for
/// bit (tests/image/tone_mapping_test.cpp checks every float around every step).
///
/// Lookup: t ∈ [0, 1) falls in one of kBuckets equal buckets, whose first code
/// is tabulated; the steepest part of the curve (the knee, 255 · 12.92 codes per
/// unit) crosses fewer than one step per bucket, so at most a step or two
/// remain to compare. NaN and t ≤ 0 give 0, t ≥ 1 gives 255.
class SrgbQuantizer {
 public:
  SrgbQuantizer();
  std::uint8_t operator()(float linear) const {
    if (!(linear > 0.0f)) return 0;  // also NaN
    if (linear >= 1.0f) return 255;
    int code = bucket_code_[static_cast<unsigned>(linear * float(kBuckets))];  // exact scaling by 2^12
    while (linear >= step_[code + 1]) ++code;
    return static_cast<std::uint8_t>(code);
  }
  /// The smallest float t whose code is ≥ `code` (1..255).
  float step(int code) const { return step_[code]; }

 private:
  static constexpr int kBuckets = 4096;
  /// step_[k]: smallest t with code(t) ≥ k, for k = 1..255; step_[256] = +∞ ends the scan.
  std::array<float, 257> step_{};
  std::array<std::uint8_t, kBuckets> bucket_code_{};  ///< code of t = i / kBuckets
};

}  // namespace zenith::image
