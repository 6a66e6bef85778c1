#pragma once
// The display encoding: from display-linear values (a fraction of the
// display's full white, after tone mapping and the output stage) to the
// numbers sent to the display. sRGB (IEC 61966-2-1, what the PNG writer and
// the default window use) or a pure power law for projectors calibrated to a
// gamma (V = L^(1/γ)). The GPU's display pass (shaders/render/display_transform.glsl)
// implements the same functions: change both together.
#include <cstdint>
#include <string>

namespace zenith::image {

struct DisplayEncoding {
  enum class Transfer {
    srgb,   ///< IEC 61966-2-1 (srgb_encode of tone_mapping.h)
    gamma,  ///< V = L^(1/gamma)
  };
  Transfer transfer = Transfer::srgb;
  double gamma = 2.2;  ///< gamma only: the display's exponent, in [kMinDisplayGamma, kMaxDisplayGamma]

  bool operator==(const DisplayEncoding&) const = default;
};
inline constexpr double kMinDisplayGamma = 1.0;
inline constexpr double kMaxDisplayGamma = 3.0;

/// The encoded value of a display-linear value, clamped to [0, 1] (NaN → 0).
float display_encode(float linear, const DisplayEncoding& encoding);
/// round((2^bits − 1) · display_encode(linear)) for bits 8 or 16: the code an
/// RGBA8 or RGBA16 display texture holds.
std::uint16_t display_code(float linear, const DisplayEncoding& encoding, int bits);
/// "sRGB", "gamma 2.4".
std::string describe(const DisplayEncoding& encoding);

}  // namespace zenith::image
