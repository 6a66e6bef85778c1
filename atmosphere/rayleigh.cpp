#include "atmosphere/rayleigh.h"

#include "atmosphere/constants.h"

namespace zenith::atmosphere {

double king_factor(double depolarization) { return (6.0 + 3.0 * depolarization) / (6.0 - 7.0 * depolarization); }

double rayleigh_scattering_coefficient(double wavelength_nm, double refractive_index, double number_density_m3,
                                       double depolarization) {
  const double lambda_m = wavelength_nm * 1e-9;
  const double n2m1 = refractive_index * refractive_index - 1.0;
  const double lambda4 = lambda_m * lambda_m * lambda_m * lambda_m;
  return 8.0 * kPi * kPi * kPi * n2m1 * n2m1 / (3.0 * number_density_m3 * lambda4) * king_factor(depolarization);
}

double rayleigh_scattering_coefficient_scaled(double wavelength_nm, double reference_refractive_index,
                                              double reference_number_density_m3, double number_density_m3,
                                              double depolarization) {
  // β(N) = 8π³ (n_ref² − 1)² / (3 N_ref λ⁴) f(δ) · (N / N_ref): the cross section
  // σ = β_ref / N_ref is a molecular property, β(N) = σ N.
  return rayleigh_scattering_coefficient(wavelength_nm, reference_refractive_index, reference_number_density_m3,
                                         depolarization) *
         (number_density_m3 / reference_number_density_m3);
}

double small_particle_absorption_coefficient(double wavelength_nm, std::complex<double> index, double radius_m,
                                             double number_density_m3) {
  const double lambda_m = wavelength_nm * 1e-9;
  const std::complex<double> n2 = index * index;
  const double im = ((n2 - 1.0) / (n2 + 2.0)).imag();
  return 8.0 * kPi * kPi * radius_m * radius_m * radius_m * number_density_m3 / lambda_m * im;
}

double standard_air_refractive_index(double wavelength_nm) {
  const double sigma = 1000.0 / wavelength_nm;  // µm^-1
  const double s2 = sigma * sigma;
  return 1.0 + (6432.8 + 2949810.0 / (146.0 - s2) + 25540.0 / (41.0 - s2)) * 1e-8;
}

double number_density_from_pressure(double pressure_Pa, double temperature_K) {
  return pressure_Pa / (kBoltzmann_J_per_K * temperature_K);
}

double number_density_from_mass_density(double mass_density_kg_m3, double molar_mass_kg_mol) {
  return kAvogadro_per_mol * mass_density_kg_m3 / molar_mass_kg_mol;
}

double scale_height(double temperature_K, double molar_mass_kg_mol, double gravity_m_s2) {
  return kGasConstant_J_per_mol_K * temperature_K / (molar_mass_kg_mol * gravity_m_s2);
}

}  // namespace zenith::atmosphere
