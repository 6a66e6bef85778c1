#pragma once
// From exposed linear radiance to display values. The GPU resolve pass
// (shaders/resolve.comp) implements the same operators: change both together.
#include <cstdint>
#include <string>

namespace zenith::image {

enum class ToneMapping {
  exponential,  ///< the paper's operator: 1 − exp(−x) (x = exposure · radiance)
  clamp,        ///< min(x, 1): no compression (for linear checks)
};
/// "exponential", "clamp"; parse throws std::invalid_argument naming the allowed values.
const char* to_string(ToneMapping tone);
ToneMapping parse_tone_mapping(const std::string& text);

/// The operator itself, for x ≥ 0 (negative and NaN give 0).
float tone_map(float x, ToneMapping tone);
/// IEC 61966-2-1 sRGB transfer function of a linear value in [0, 1] (clamped).
float srgb_encode(float linear);
float srgb_decode(float encoded);
/// round(255 · srgb_encode(tone_map(x))).
std::uint8_t display_byte(float x, ToneMapping tone);

/// d/dx of tone_map(x) for x ≥ 0, the right derivative at a kink: e^(−x) for
/// the exponential operator; 1 below 1 and 0 from 1 for clamp. Both operators
/// are concave and non-decreasing on x ≥ 0, so the slope at x bounds it at any x' ≥ x.
double tone_map_slope(double x, ToneMapping tone);
/// d/dL of srgb_encode(L) for L ≥ 0, the right derivative: 12.92 on the
/// linear toe (L ≤ 0.0031308), (1.055 / 2.4) L^(1/2.4 − 1) above it (12.703
/// at the toe's end, falling), 0 from 1. Non-increasing; the two branches
/// meet 2.9e-8 lower on the power branch's side, a step down, so
/// srgb_encode(L + Δ) − srgb_encode(L) ≤ srgb_encode_slope(L) · Δ for Δ ≥ 0.
double srgb_encode_slope(double linear);
/// The largest rate at which an 8-bit display code, 255 · srgb_encode(tone_map(x)),
/// can change with x at any x' ≥ x ≥ 0, over both operators [codes per unit
/// of exposed radiance]: 255 · max over the operators of E'(T(x)) T'(x). The
/// composition of concave non-decreasing functions is concave, so a change
/// of x by |Δ| from any x' ≥ x moves the code value by at most this · |Δ|.
double display_code_slope_bound(double x);

}  // namespace zenith::image
