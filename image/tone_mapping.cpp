#include "image/tone_mapping.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace zenith::image {

const char* to_string(ToneMapping tone) {
  switch (tone) {
    case ToneMapping::exponential: return "exponential";
    case ToneMapping::clamp: return "clamp";
  }
  return "?";
}

ToneMapping parse_tone_mapping(const std::string& text) {
  if (text == "exponential") return ToneMapping::exponential;
  if (text == "clamp") return ToneMapping::clamp;
  throw std::invalid_argument("unknown tone mapping '" + text + "': must be one of exponential, clamp");
}

float tone_map(float x, ToneMapping tone) {
  if (!(x > 0.0f)) return 0.0f;  // negative, zero and NaN
  switch (tone) {
    // Costa et al.'s exposure operator 1 − exp(−x), written as −expm1(−x) so that
    // small x keep their relative precision (1 − exp(−x) would cancel). +∞ → 1.
    case ToneMapping::exponential: return -std::expm1(-x);
    case ToneMapping::clamp: return std::fmin(x, 1.0f);
  }
  return 0.0f;
}

// IEC 61966-2-1:1999 (sRGB), section 5.2 (encoding) and 5.3 (decoding):
//   V = 12.92 L                     for L ≤ 0.0031308
//   V = 1.055 L^(1/2.4) − 0.055     otherwise
//   L = V / 12.92                   for V ≤ 0.04045
//   L = ((V + 0.055) / 1.055)^2.4   otherwise
// Evaluated in double and rounded once to float. The two branches leave a gap
// (12.92 · 0.0031308 = 0.0404499 < 0.04045 < the power branch's 0.040452 there),
// so decode(encode(L)) picks the matching branch and round-trips.
float srgb_encode(float linear) {
  if (!(linear > 0.0f)) return 0.0f;  // also NaN
  if (linear >= 1.0f) return 1.0f;
  const double l = linear;
  const double v = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
  return static_cast<float>(v);
}

float srgb_decode(float encoded) {
  if (!(encoded > 0.0f)) return 0.0f;  // also NaN
  if (encoded >= 1.0f) return 1.0f;
  const double v = encoded;
  const double l = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  return static_cast<float>(l);
}

std::uint8_t display_byte(float x, ToneMapping tone) {
  const float encoded = srgb_encode(tone_map(x, tone));  // in [0, 1]
  return static_cast<std::uint8_t>(std::lround(255.0f * encoded));
}

double tone_map_slope(double x, ToneMapping tone) {
  const double at = std::max(x, 0.0);
  switch (tone) {
    case ToneMapping::exponential: return std::exp(-at);
    case ToneMapping::clamp: return at < 1.0 ? 1.0 : 0.0;
  }
  return 1.0;
}

double srgb_encode_slope(double linear) {
  const double l = std::max(linear, 0.0);
  if (l >= 1.0) return 0.0;
  if (l <= 0.0031308) return 12.92;
  return 1.055 / 2.4 * std::pow(l, 1.0 / 2.4 - 1.0);
}

double display_code_slope_bound(double x) {
  const double at = std::max(x, 0.0);
  double slope = 0.0;
  for (ToneMapping tone : {ToneMapping::exponential, ToneMapping::clamp}) {
    const double t = tone == ToneMapping::exponential ? -std::expm1(-at) : std::min(at, 1.0);
    slope = std::max(slope, srgb_encode_slope(t) * tone_map_slope(at, tone));
  }
  return 255.0 * slope;
}

}  // namespace zenith::image
