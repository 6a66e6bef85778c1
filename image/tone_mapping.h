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

}  // namespace zenith::image
