#pragma once
// From per-wavelength radiance (per unit solar irradiance, as the tables and
// the reference solver give it) to physical spectral radiance and luminance.
#include <span>
#include <vector>

namespace zenith::atmosphere {

/// Extraterrestrial solar spectral irradiance at 1 AU [W m^-2 nm^-1]
/// (Kurucz 1992, 10 nm bins, 360–830 nm; nearest bin outside).
double solar_irradiance_W_m2_nm(double wavelength_nm);

/// CIE 1924 photopic luminous efficiency V(λ), linear between 10 nm samples, 0 outside 380–780 nm.
double photopic_efficiency(double wavelength_nm);

/// Luminance weights w_i such that Y = Σ w_i L_i [cd m^-2] for spectral
/// radiances L_i [W m^-2 sr^-1 nm^-1] at the working wavelengths:
///   w_i = 683 lm/W · V(λ_i) · Δλ_i,
/// with Δλ_i the width of the wavelength's bin under the midpoint rule (half
/// the distance to each neighbour; for one wavelength, 100 nm). With the paper's
/// three wavelengths this is a coarse quadrature of ∫ V L dλ; ratios such as
/// L/L_zenith (the CIE comparison) are what it is meant for.
std::vector<double> luminance_weights(std::span<const double> wavelengths_nm);

}  // namespace zenith::atmosphere
