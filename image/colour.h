#pragma once
// Colour of spectral quantities at the working wavelengths: radiance at N
// wavelengths → linear sRGB for output, and linear sRGB reflectances (albedo
// colours and maps) → a reflectance at each wavelength. docs/colour.md explains both.
#include <array>
#include <span>
#include <string>
#include <vector>

namespace zenith::image {

enum class ColourMapping {
  automatic,  ///< direct when there are exactly 3 wavelengths, one in each of the R, G, B bands below; cie1931
              ///< otherwise
  direct,     ///< the paper's: the 3 wavelengths (sorted, longest first) are R, G, B as they are; needs exactly 3
  cie1931,    ///< Σ radiance · CIE 1931 2° colour matching functions · bin width → XYZ → Bradford adaptation
              ///< from the equal-energy white (the spectrally flat sun of per-unit-irradiance radiance) to
              ///< D65 → linear sRGB; needs wavelengths spanning the visible range (≳ 16 for white within 3 %)
};
/// "auto", "direct", "cie1931"; parse throws std::invalid_argument naming the allowed values.
const char* to_string(ColourMapping mapping);
ColourMapping parse_colour_mapping(const std::string& text);

/// Per wavelength, the weights of its radiance in R, G, B: rgb = Σ_i weights[i] · L_i.
/// Direct: the R band is [600, 750] nm, G [500, 600) nm, B [380, 500) nm. Throws
/// std::invalid_argument when `mapping` is direct and the wavelengths do not fit it,
/// and for no wavelengths, non-finite or non-positive ones, repeated ones, or (cie1931)
/// wavelengths outside the visible range. The cie1931 weights are scaled so that a
/// spectrally flat radiance of 1 maps to luminance Y = 1 (so direct and cie1931 give
/// comparable magnitudes); it maps to white within 0.5 % at 64 wavelengths over 380–780 nm.
std::vector<std::array<double, 3>> spectral_to_rgb_weights(std::span<const double> wavelengths_nm,
                                                           ColourMapping mapping);

/// Per wavelength, the weights of R, G, B in its reflectance: ρ_i = Σ_c weights[i][c] · rgb_c,
/// for linear sRGB reflectances. With `direct` (and `automatic` where direct applies)
/// weights[i] picks the channel of λ_i's band, so a colour round-trips through the direct
/// mapping; otherwise the reflectance is piecewise linear in λ through (450 nm, B),
/// (550 nm, G), (650 nm, R), constant beyond, so white (1, 1, 1) is 1 at every wavelength.
/// Throws std::invalid_argument as spectral_to_rgb_weights does (repeats are allowed).
std::vector<std::array<double, 3>> rgb_to_spectral_weights(std::span<const double> wavelengths_nm,
                                                           ColourMapping mapping);

}  // namespace zenith::image
