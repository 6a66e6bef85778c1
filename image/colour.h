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

/// CIE 1931 chromaticity.
struct Chromaticity {
  double x = 0.0, y = 0.0;
};

/// The chromaticity of a spectrum sampled at `wavelengths_nm` (any unit of
/// spectral radiance; its absolute colour, no adaptation):
///   (X, Y, Z) = Σ_i S_i · (x̄, ȳ, z̄)(λ_i) · Δλ_i,   x = X / (X + Y + Z),  y = Y / (X + Y + Z),
/// with the cie1931 mapping's colour matching functions and midpoint bins.
/// Meaningful only where the wavelengths span the visible range densely
/// (colour_spectrum_problem). Throws std::invalid_argument for wavelengths
/// spectral_to_rgb_weights refuses, a spectrum not one value per wavelength,
/// a negative or non-finite value, or no light (X + Y + Z = 0).
Chromaticity spectrum_chromaticity(std::span<const double> wavelengths_nm, std::span<const double> spectrum);

/// Why `wavelengths_nm` cannot give a spectrum's colour, or empty if they
/// can: at least 16 wavelengths, from 400 nm or below to 700 nm or above
/// (where a flat spectrum comes out white within 3 %, docs/colour.md).
std::string colour_spectrum_problem(std::span<const double> wavelengths_nm);

/// The correlated colour temperature of a chromaticity (CIE 15): the
/// temperature of the Planckian radiator whose chromaticity is nearest in the
/// CIE 1960 (u, v) plane, u = 4x / (−2x + 12y + 3), v = 6y / (−2x + 12y + 3);
/// and Duv, that distance, positive above the locus (toward green). The
/// locus is Planck's law (core/planck.h) through the same colour matching functions (360–830
/// nm every nm), searched over 1 000 K – 1 000 000 K; a chromaticity beyond
/// the locus' blue end (bluer than any Planckian radiator, nearest to its
/// T → ∞ limit) has kelvin = +∞, Duv its distance from that end. CIE 15
/// calls a CCT meaningful within |Duv| ≤ 0.05. Throws std::invalid_argument
/// for (x, y) outside the chromaticity triangle x, y > 0, x + y < 1.
struct ColourTemperature {
  double kelvin = 0.0;
  double duv = 0.0;
};
ColourTemperature correlated_colour_temperature(Chromaticity c);

/// The effective blackbody temperature of a spectrum over [`from_nm`,
/// `to_nm`]: the temperature of the Planck curve whose shape fits the
/// spectrum there best, least squares in ln S (a free scale), as eclipse
/// photometry reports the sky's colour (Dandekar & Turtle 1971: 410–800 nm).
/// Searched over 1 000 K – 10⁸ K; a spectrum falling faster with wavelength
/// than any Planck curve (steeper than the Rayleigh–Jeans λ⁻⁴) fits best at
/// the hot end and gives +∞. Throws std::invalid_argument for fewer than 3
/// wavelengths in the band, a spectrum not one value per wavelength, or a
/// value in the band that is not finite and positive.
double effective_blackbody_temperature_K(std::span<const double> wavelengths_nm, std::span<const double> spectrum,
                                         double from_nm, double to_nm);

}  // namespace zenith::image
