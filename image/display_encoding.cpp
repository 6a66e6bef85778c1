#include "image/display_encoding.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "image/tone_mapping.h"

namespace zenith::image {

float display_encode(float linear, const DisplayEncoding& encoding) {
  if (encoding.transfer == DisplayEncoding::Transfer::srgb) return srgb_encode(linear);
  if (!(linear > 0.0f)) return 0.0f;  // also NaN
  if (linear >= 1.0f) return 1.0f;
  return static_cast<float>(std::pow(static_cast<double>(linear), 1.0 / encoding.gamma));
}

std::uint16_t display_code(float linear, const DisplayEncoding& encoding, int bits) {
  if (bits != 8 && bits != 16) throw std::invalid_argument(fmt::format("display_code: {} bits (8 or 16)", bits));
  const float top = bits == 8 ? 255.0f : 65535.0f;
  return static_cast<std::uint16_t>(std::lround(top * display_encode(linear, encoding)));
}

std::string describe(const DisplayEncoding& encoding) {
  if (encoding.transfer == DisplayEncoding::Transfer::srgb) return "sRGB";
  return fmt::format("gamma {}", encoding.gamma);
}

}  // namespace zenith::image
