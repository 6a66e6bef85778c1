#pragma once
// A star as a point source of light: its spectral irradiance at the top of the
// atmosphere from its V magnitude and B−V colour (docs/night-sky.md, "Stars").
//
// Colour → temperature: Ballesteros (2012, EPL 97, 34008), a blackbody fit to
// the B and V bands,
//   T = 4600 K · ( 1/(0.92 (B−V) + 1.7) + 1/(0.92 (B−V) + 0.62) ),
// 9 700 K at B−V = 0, 5 800 K at 0.65 (the Sun: 5 772 K), 3 900 K at 1.5.
// Spectrum: Planck's B_λ(T) scaled so that its V-band mean (v_band.h) is the
// star's V: E(λ) = f₀ 10^(−0.4 V) B_λ(T, λ) / ⟨B_λ(T)⟩_V [W m⁻² nm⁻¹].
// A blackbody misses the Balmer jump and the molecular bands of cool stars;
// at the working wavelengths (400–700 nm) that is a few per cent for A–K stars
// and up to ~20 % in the blue for M stars, below what the eye tells.
// The renderer attenuates E by the line of sight's transmittance and adds it,
// spread over the pixel's solid angle, to the sky's radiance.
#include <span>
#include <vector>

#include "core/planck.h"

namespace zenith::astro {

/// Ballesteros' colour temperature [K] of B−V, for B−V in [−0.4, 2.5] (clamped).
double ballesteros_temperature_K(double b_minus_v);
/// Planck's spectral radiance B_λ(T) [W m⁻² sr⁻¹ nm⁻¹] (core/planck.h).
using core::planck_W_m2_sr_nm;

/// The star's spectral irradiance at `wavelengths_nm` above the atmosphere [W m⁻² nm⁻¹].
std::vector<double> star_irradiance_W_m2_nm(double v_mag, double b_minus_v, std::span<const double> wavelengths_nm);
/// The same into `out` (size of wavelengths), without allocating (per-star loops).
void star_irradiance_W_m2_nm(double v_mag, double b_minus_v, std::span<const double> wavelengths_nm,
                             std::span<double> out);

}  // namespace zenith::astro
