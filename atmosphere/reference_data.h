#pragma once
// Published tables compiled into the binary (copied from ../shared/data/ with
// their source lines; see atmosphere/data/).
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "atmosphere/density_profile.h"
#include "atmosphere/spectrum.h"

namespace zenith::atmosphere {

/// Contents of an embedded file ("data/us_standard_atmosphere_1976.csv",
/// "atmospheres/earth-standard.json", ...). Throws std::out_of_range if absent.
std::string_view embedded_file(std::string_view name);
/// Names of the embedded files under a prefix ("atmospheres/").
std::vector<std::string> embedded_files_under(std::string_view prefix);

/// One column of the U.S. Standard Atmosphere 1976 constituent profile
/// (AFGL-TR-86-0110): altitudes [m] and number densities [m^-3].
struct StandardAtmosphereColumn {
  std::vector<double> altitude_m;
  std::vector<double> number_density_m3;
};
/// `species` is a CSV column: "air", "o3", "o2", "h2o", "co2", "no2".
StandardAtmosphereColumn us_standard_atmosphere_1976(const std::string& species);

/// Ozone profile of the US Standard Atmosphere 1976 as a monotone cubic spline
/// (paper section 4.2.2), relative to its peak number density, which is returned
/// in `peak_number_density_m3`.
DensityProfile us_standard_1976_profile(const std::string& species, double* peak_number_density_m3);

/// Ozone absorption cross section [m^2] at `wavelength_nm` and `temperature_K`
/// (Bogumil et al. 2003 temperature fit, 10 nm bins, 360–830 nm): linear in
/// wavelength between bins and linear in temperature between the 233 K and 293 K
/// columns. Returns false in `covered` when the wavelength is outside the table.
double ozone_cross_section_m2(double wavelength_nm, double temperature_K, bool* covered = nullptr);

/// One row of Neckel & Labs (1994)'s solar limb darkening
/// (atmosphere/solar_limb_darkening.h): the continuum wavelength, the
/// coefficients a_0 … a_5 of I(μ)/I(1) = Σ a_k μ^k, and the disc's mean
/// intensity over its centre's as they tabulate it.
struct LimbDarkeningRow {
  double wavelength_nm = 0.0;
  std::array<double, 6> coefficients{};
  double mean_over_centre = 0.0;
};
/// The 30 rows, 303–1099 nm, by increasing wavelength.
const std::vector<LimbDarkeningRow>& neckel_labs_1994_limb_darkening();

}  // namespace zenith::atmosphere
