#pragma once
// Scattering and extinction by large particles (paper section 4.3).
#include <complex>

namespace zenith::atmosphere {

/// Concentration factor of the turbidity model (Preetham et al. 1999, as used by
/// Morales 2017 and the paper): C(T) = (0.65 T − 0.65)·10⁻¹⁶. T = 1 is a pure
/// molecular atmosphere (C = 0); the paper uses T ∈ [2, 10].
double turbidity_concentration(double turbidity);

/// Mie scattering coefficient at the reference altitude from turbidity, paper eq. (17):
///   β_M^scat(λ) = 0.434 C(T) π (2π/λ)^{ν−2} K(λ)   [m^-1], λ in metres.
/// ν is Junge's exponent (ν ∈ [2, 6], ν = 4 gives a λ^-2 law), K(λ) Götz's
/// wavelength-dependent factor (dimensionless).
double mie_scattering_from_turbidity(double wavelength_nm, double turbidity, double junge_exponent, double K);

/// Extinction efficiency of an absorbing sphere in the anomalous-diffraction
/// approximation (van de Hulst 1981, §11.22), paper eq. (19):
///   Q = 2 − 4 e^{−ρ tanβ} (cosβ/ρ) sin(ρ−β) − 4 e^{−ρ tanβ} (cosβ/ρ)² cos(ρ−2β) + 4 (cosβ/ρ)² cos2β,
///   ρ = 4π r (m − 1)/λ,  tanβ = k/(m − 1),  index = m + k i with m > 1, k ≥ 0.
/// Evaluated as Q = 4 Re K(w), K(w) = ½ + e^{−w}/w + (e^{−w} − 1)/w², w = ρ(tanβ + i),
/// which is algebraically identical and, through its power series for small |w|,
/// free of the catastrophic cancellation eq. (19) suffers as ρ → 0 (Q ~ ρ²/2).
double anomalous_diffraction_extinction_efficiency(double wavelength_nm, std::complex<double> index, double radius_m);

/// Absorption efficiency of the same sphere in the anomalous-diffraction
/// approximation (van de Hulst 1981, §11.22):
///   Q_abs = 1 + e^{−2y}/y + (e^{−2y} − 1)/(2y²),   y = 2 x k = 4π r k/λ.
/// Q_abs/Q_ext is the co-albedo 1 − ω; the Mars and Titan presets pick Götz's
/// K(λ) so that eq. (17) gives ω·β^ext (see docs/presets.md).
double anomalous_diffraction_absorption_efficiency(double wavelength_nm, double imag_index, double radius_m);

/// Mean-radius Mie extinction coefficient at the reference altitude, paper eq. (20):
///   β_M^ext(λ) = π r̄² Q̄(λ, ρ(r̄)) N_r̄   [m^-1].
/// (Eq. (18) prints the height term with H_R; the aerosol profile uses H_M, as in eq. (20).)
double mie_extinction_anomalous_diffraction(double wavelength_nm, std::complex<double> index, double mean_radius_m,
                                            double number_density_m3);

}  // namespace zenith::atmosphere
