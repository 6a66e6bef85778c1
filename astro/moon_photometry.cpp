#include "astro/moon_photometry.h"

#include <cmath>

#include "astro/v_band.h"
#include "atmosphere/photometry.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

constexpr double kFullMoonV = -12.73;  // Allen 1973 / Krisciunas & Schaefer 1991, at 384 400 km
constexpr double kMeanDistance_km = 384400.0;
constexpr double kReflectanceSlope_per_nm = 0.0020;

double reflectance_shape(double wavelength_nm) { return 1.0 + kReflectanceSlope_per_nm * (wavelength_nm - 550.0); }

/// p(550): the full Moon at the mean distance shows kFullMoonV with the Kurucz Sun.
double albedo_at_550() {
  static const double p = [] {
    const double sun =
        v_band_mean([](double l) { return atmosphere::solar_irradiance_W_m2_nm(l) * reflectance_shape(l); });
    const double solid = std::pow(kMoonRadius_km / kMeanDistance_km, 2.0);
    return v_irradiance_W_m2_nm(kFullMoonV) / (sun * solid);
  }();
  return p;
}

}  // namespace

double lommel_seeliger_phase(double a) {
  a = std::abs(a);
  if (a < 1e-9) return 1.0;
  if (a >= core::kPi) return 0.0;
  return 1.0 - std::sin(0.5 * a) * std::tan(0.5 * a) * std::log(1.0 / std::tan(0.25 * a));
}

double lunar_phase_law(double a) {
  const double deg = std::abs(a) / core::kDeg;
  return std::pow(10.0, -0.4 * (0.026 * deg + 4e-9 * deg * deg * deg * deg));
}

double lunar_geometric_albedo(double wavelength_nm) { return albedo_at_550() * reflectance_shape(wavelength_nm); }

double moon_v_magnitude(double phase_angle_rad, double distance_km, double sun_distance_au) {
  const double sun =
      v_band_mean([](double l) { return atmosphere::solar_irradiance_W_m2_nm(l) * lunar_geometric_albedo(l); });
  const double e = sun / (sun_distance_au * sun_distance_au) * lunar_phase_law(phase_angle_rad) *
                   std::pow(kMoonRadius_km / distance_km, 2.0);
  return v_magnitude(e);
}

std::vector<double> moon_irradiance_W_m2_nm(const MoonPlace& moon, std::span<const double> wavelengths_nm) {
  std::vector<double> out;
  const double geometry = lunar_phase_law(moon.phase_angle_rad) * std::pow(kMoonRadius_km / moon.distance_km, 2.0) /
                          (moon.sun_distance_au * moon.sun_distance_au);
  for (double l : wavelengths_nm)
    out.push_back(atmosphere::solar_irradiance_W_m2_nm(l) * lunar_geometric_albedo(l) * geometry);
  return out;
}

double moon_disc_radiance(double mu0, double mu, double phase_angle_rad, double wavelength_nm, double sun_distance_au) {
  if (mu0 <= 0.0 || mu <= 0.0) return 0.0;
  // Disc-integral of L = K μ₀/(μ₀+μ) over the visible disc is K π R² Φ_LS(α) / (2 d²); the
  // irradiance is E p Φ(α) R²/d², so K = 2 E p Φ(α) / (π Φ_LS(α)).
  const double ls = lommel_seeliger_phase(phase_angle_rad);
  if (ls <= 0.0) return 0.0;
  const double e = atmosphere::solar_irradiance_W_m2_nm(wavelength_nm) / (sun_distance_au * sun_distance_au);
  const double k =
      2.0 * e * lunar_geometric_albedo(wavelength_nm) * lunar_phase_law(phase_angle_rad) / (core::kPi * ls);
  return k * mu0 / (mu0 + mu);
}

}  // namespace zenith::astro
