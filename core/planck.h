#pragma once
// Planck's law, one spelling for every module: the stars' and the city
// lights' spectra (astro/), the Planckian locus and the effective blackbody
// temperature of a spectrum (image/colour.h).
#include <cmath>

namespace zenith::core {

/// The SI defining constants (exact since 2019).
inline constexpr double kPlanck_J_s = 6.62607015e-34;
inline constexpr double kSpeedOfLight_m_s = 299792458.0;
inline constexpr double kBoltzmann_J_K = 1.380649e-23;

/// Planck's spectral radiance B_λ(T) = 2 h c² / λ⁵ / (exp(h c / λ k T) − 1) [W m⁻² sr⁻¹ nm⁻¹].
inline double planck_W_m2_sr_nm(double wavelength_nm, double temperature_K) {
  const double l = wavelength_nm * 1e-9;
  const double per_m = 2.0 * kPlanck_J_s * kSpeedOfLight_m_s * kSpeedOfLight_m_s / (l * l * l * l * l) /
                       std::expm1(kPlanck_J_s * kSpeedOfLight_m_s / (l * kBoltzmann_J_K * temperature_K));
  return per_m * 1e-9;  // per metre → per nanometre
}

}  // namespace zenith::core
