#pragma once
// Scattering and absorption by molecules (paper section 4.1 and 4.2).
#include <complex>

namespace zenith::atmosphere {

/// King correction factor for anisotropic molecules, paper eq. (11) (Liou 2002):
///   f(δ) = (6 + 3δ) / (6 − 7δ),   δ ∈ [0, 6/7) the depolarization factor.
/// f(0.0279) = 1.04806 (air), f(0.09) = 1.1676 (CO2-like).
double king_factor(double depolarization);

/// Rayleigh–Cabannes volume scattering coefficient at the reference density,
/// paper eq. (11) without the height term:
///   β_R^scat(λ) = 8π³ (n(λ)² − 1)² / (3 N λ⁴) · f(δ)   [m^-1]
/// `refractive_index` is the real index of the gas at number density
/// `number_density_m3` [m^-3]; `wavelength_nm` in nanometres.
double rayleigh_scattering_coefficient(double wavelength_nm, double refractive_index, double number_density_m3,
                                       double depolarization);

/// Same coefficient for a gas whose refractive index was measured at a different
/// number density N_ref: (n − 1) is proportional to N (Lorentz–Lorenz in the
/// dilute limit), so β ∝ (n_ref² − 1)² N / N_ref². This lets a preset use a
/// tabulated standard-condition index (e.g. CO2 at STP) for a thin atmosphere.
double rayleigh_scattering_coefficient_scaled(double wavelength_nm, double reference_refractive_index,
                                              double reference_number_density_m3, double number_density_m3,
                                              double depolarization);

/// Absorption coefficient of small absorbing molecules or particles of radius r,
/// paper eq. (12) (Bohren & Huffman 1983, first term of the Mie series):
///   β_R^abs(λ) = 8π² r³ N / λ · Im((n² − 1)/(n² + 2))   [m^-1]
/// `index` is the complex refractive index m + k i (k ≥ 0 absorbs).
double small_particle_absorption_coefficient(double wavelength_nm, std::complex<double> index, double radius_m,
                                             double number_density_m3);

/// Refractive index of standard air (15 °C, 1013.25 hPa, 0.03 % CO2) after Edlén
/// (1953) as tabulated by Penndorf (1957):
///   (n − 1)·10⁸ = 6432.8 + 2949810/(146 − σ²) + 25540/(41 − σ²),  σ = 1/λ [µm^-1].
/// Gives 1.00027598, 1.00027783, 1.00028091 at 680, 550, 440 nm. (Table 1 of the
/// paper prints 1.00028276 for 440 nm, which is this formula's value at 400 nm.)
/// Valid 200–2000 nm. Its number density is kStandardAirNumberDensity_m3.
double standard_air_refractive_index(double wavelength_nm);

/// Number density of standard air (15 °C, 1013.25 hPa) that goes with
/// standard_air_refractive_index, as Penndorf (1957) gives it: 2.547e25 m^-3
/// (p/(k_B T) = 2.5469e25 m^-3 at 15 °C, 1013.25 hPa).
inline constexpr double kStandardAirNumberDensity_m3 = 2.547e25;

/// Ideal gas: number density N = p / (k_B T) [m^-3].
double number_density_from_pressure(double pressure_Pa, double temperature_K);
/// Number density from mass density and mean molar mass: N = N_A ρ / M [m^-3].
double number_density_from_mass_density(double mass_density_kg_m3, double molar_mass_kg_mol);
/// Isothermal scale height H = R T / (M g) [m].
double scale_height(double temperature_K, double molar_mass_kg_mol, double gravity_m_s2);

}  // namespace zenith::atmosphere
