#include "astro/light_pollution.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "astro/range_check.h"
#include "astro/star_photometry.h"
#include "astro/v_band.h"
#include "atmosphere/air_mass.h"
#include "atmosphere/spectrum.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

std::vector<double> scattering_depth(const atmosphere::AtmosphereModel& model) {
  const auto d = model.zenith_optical_depth();
  std::vector<double> tau(model.wavelength_count());
  for (std::size_t i = 0; i < tau.size(); ++i) tau[i] = d.rayleigh[i] + d.mie_scattering[i];
  return tau;
}

/// The glow's relative spectral shape: lamp blackbody × scattering depth relative to its value at 550 nm.
struct GlowShape {
  GlowShape(const std::vector<double>& wavelengths_nm, const std::vector<double>& tau, double temperature)
      : temperature_K(temperature) {
    std::vector<std::pair<double, double>> samples;
    for (std::size_t i = 0; i < tau.size(); ++i) samples.emplace_back(wavelengths_nm[i], tau[i]);
    depth = atmosphere::SpectralTable(std::move(samples));  // linear between samples, nearest outside
  }
  atmosphere::SpectralTable depth;
  double temperature_K;
  double operator()(double l) const { return planck_W_m2_sr_nm(l, temperature_K) * depth(l) / depth(550.0); }
};

}  // namespace

double bortle_zenith_v_mag_arcsec2(int bortle_class) {
  static constexpr double kMid[9] = {21.99, 21.94, 21.79, 21.09, 20.0, 19.22, 18.66, 18.0, 17.5};
  if (bortle_class < 1 || bortle_class > 9)
    throw std::invalid_argument("Bortle class " + std::to_string(bortle_class) + ": must be in [1, 9]");
  return kMid[bortle_class - 1];
}

LightPollution::LightPollution(const atmosphere::AtmosphereModel& model, const LightPollutionOptions& options)
    : wavelengths_nm_(model.wavelengths_nm),
      scattering_depth_(scattering_depth(model)),
      zenith_mcd_m2_(options.zenith_mcd_m2) {
  require_in_range("light pollution zenith_mcd_m2", options.zenith_mcd_m2, 0.0, 1e5, "mcd/m^2");
  require_in_range("light pollution colour_temperature_K", options.colour_temperature_K, 1500.0, 10000.0, "K");
  const GlowShape shape{wavelengths_nm_, scattering_depth_, options.colour_temperature_K};
  const double scale = options.zenith_mcd_m2 * 1e-3 / luminance_cd_m2(shape);
  for (double l : wavelengths_nm_) zenith_radiance_.push_back(scale * shape(l));
}

double LightPollution::gradient(double zenith_angle_rad, std::size_t i) const {
  const double altitude_deg = std::max(0.0, 90.0 - std::min(std::abs(zenith_angle_rad), 0.5 * core::kPi) / core::kDeg);
  const double x = atmosphere::pickering_air_mass(altitude_deg);
  const double tau = std::max(scattering_depth_[i], 1e-9);
  return -std::expm1(-tau * x) / -std::expm1(-tau);
}

std::vector<double> LightPollution::radiance(double zenith_angle_rad) const {
  std::vector<double> out(zenith_radiance_.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = zenith_radiance_[i] * gradient(zenith_angle_rad, i);
  return out;
}

double bortle_artificial_mcd_m2(int bortle_class, const atmosphere::AtmosphereModel& model, double natural_cd_m2,
                                double colour_temperature_K) {
  const GlowShape shape{model.wavelengths_nm, scattering_depth(model), colour_temperature_K};
  // cd m⁻² per unit of V-band mean radiance, for this glow's spectrum.
  const double luminance_per_v = luminance_cd_m2(shape) / v_band_mean(shape);
  const double total_cd_m2 = v_radiance_W_m2_sr_nm(bortle_zenith_v_mag_arcsec2(bortle_class)) * luminance_per_v;
  return std::max(0.0, total_cd_m2 - natural_cd_m2) * 1e3;
}

}  // namespace zenith::astro
