#include "astro/night_sky_floor.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "astro/range_check.h"
#include "astro/v_band.h"
#include "atmosphere/photometry.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

struct AirglowLine {
  double wavelength_nm, rayleighs;
};
// Leinert et al. 1998, Table 2 (typical zenith intensities).
constexpr AirglowLine kLines[] = {{557.7, 250.0}, {589.3, 50.0}, {630.0, 60.0}};
constexpr double kOutsideShareOfV = 0.45;  // zodiacal light + integrated starlight
constexpr double kReferenceZenith_mag = 22.0;

/// Radiance of a line of I rayleighs [W m⁻² sr⁻¹]: I·10¹⁰/(4π) photons s⁻¹ m⁻² sr⁻¹ times hc/λ.
double line_radiance_W_m2_sr(const AirglowLine& line) {
  constexpr double h = 6.62607015e-34, c = 299792458.0;
  return line.rayleighs * 1e10 / (4.0 * core::kPi) * h * c / (line.wavelength_nm * 1e-9);
}

}  // namespace

std::vector<double> wavelength_bin_widths_nm(std::span<const double> wavelengths_nm) {
  // Δλ by atmosphere/photometry.h's rule for luminance weights (without V(λ)).
  std::vector<double> widths(wavelengths_nm.size(), 100.0);
  std::vector<std::size_t> order(wavelengths_nm.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return wavelengths_nm[a] < wavelengths_nm[b]; });
  const std::size_t n = order.size();
  for (std::size_t k = 0; n > 1 && k < n; ++k) {
    const double x = wavelengths_nm[order[k]];
    const double lo = k > 0 ? wavelengths_nm[order[k - 1]] : 2 * x - wavelengths_nm[order[k + 1]];
    const double hi = k + 1 < n ? wavelengths_nm[order[k + 1]] : 2 * x - wavelengths_nm[order[k - 1]];
    widths[order[k]] = 0.5 * (hi - lo);
  }
  return widths;
}

NightSkyFloor::NightSkyFloor(const atmosphere::AtmosphereModel& model, const NightSkyFloorOptions& options)
    : wavelengths_nm_(model.wavelengths_nm),
      bin_width_nm_(wavelength_bin_widths_nm(model.wavelengths_nm)),
      ground_radius_m_(model.ground_radius_m) {
  require_in_range("night sky zenith_v_mag_arcsec2", options.zenith_v_mag_arcsec2, 19.0, 23.0, "mag/arcsec^2");
  require_in_range("night sky airglow_height_m", options.airglow_height_m, 1e4, 5e5, "m");
  layer_ratio_ = model.ground_radius_m / (model.ground_radius_m + options.airglow_height_m);
  const auto tau = model.zenith_optical_depth().total;
  for (std::size_t i = 0; i < wavelengths_nm_.size(); ++i) zenith_transmittance_.push_back(std::exp(-tau[i]));
  const atmosphere::SpectralTable transmittance = zenith_transmittance_table();

  // The observed zenith's V-band mean radiance, and each component's share of it.
  const double target = v_radiance_W_m2_sr_nm(options.zenith_v_mag_arcsec2);
  const double line_scale = target / v_radiance_W_m2_sr_nm(kReferenceZenith_mag);
  lines_scale_ = line_scale;
  double lines_v = 0.0;
  for (const auto& line : kLines)
    lines_v += v_band_mean_of_line(line.wavelength_nm,
                                   line_scale * line_radiance_W_m2_sr(line) * transmittance(line.wavelength_nm));
  outside_scale_ = kOutsideShareOfV * target /
                   v_band_mean([&](double l) { return atmosphere::solar_irradiance_W_m2_nm(l) * transmittance(l); });
  const double continuum_v = std::max(0.0, (1.0 - kOutsideShareOfV) * target - lines_v);
  airglow_continuum_scale_ = continuum_v / v_band_mean([&](double l) { return (l / 550.0) * transmittance(l); });

  airglow_zenith_.assign(wavelengths_nm_.size(), 0.0);
  outside_zenith_.assign(wavelengths_nm_.size(), 0.0);
  for (std::size_t i = 0; i < wavelengths_nm_.size(); ++i) {
    airglow_zenith_[i] = continuous_radiance(wavelengths_nm_[i], true);
    outside_zenith_[i] = continuous_radiance(wavelengths_nm_[i], false);
  }
  for (const auto& line : kLines) {
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < wavelengths_nm_.size(); ++i)
      if (std::abs(wavelengths_nm_[i] - line.wavelength_nm) < std::abs(wavelengths_nm_[nearest] - line.wavelength_nm))
        nearest = i;
    if (std::abs(wavelengths_nm_[nearest] - line.wavelength_nm) <= 0.5 * bin_width_nm_[nearest])
      airglow_zenith_[nearest] += line_scale * line_radiance_W_m2_sr(line) / bin_width_nm_[nearest];
  }
}

atmosphere::SpectralTable NightSkyFloor::zenith_transmittance_table() const {
  std::vector<std::pair<double, double>> samples;
  for (std::size_t i = 0; i < wavelengths_nm_.size(); ++i)
    samples.emplace_back(wavelengths_nm_[i], zenith_transmittance_[i]);
  return atmosphere::SpectralTable(std::move(samples));
}

double NightSkyFloor::continuous_radiance(double wavelength_nm, bool airglow) const {
  return airglow ? airglow_continuum_scale_ * (wavelength_nm / 550.0)
                 : outside_scale_ * atmosphere::solar_irradiance_W_m2_nm(wavelength_nm);
}

double NightSkyFloor::van_rhijn(double zenith_angle_rad) const {
  const double s = std::sin(std::min(std::abs(zenith_angle_rad), 0.5 * core::kPi));
  return 1.0 / std::sqrt(1.0 - layer_ratio_ * layer_ratio_ * s * s);
}

std::vector<double> NightSkyFloor::top_of_atmosphere_radiance(double zenith_angle_rad) const {
  const double v = van_rhijn(zenith_angle_rad);
  std::vector<double> out(wavelengths_nm_.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = airglow_zenith_[i] * v + outside_zenith_[i];
  return out;
}

std::vector<double> NightSkyFloor::observed_radiance(double zenith_angle_rad,
                                                     std::span<const double> transmittance) const {
  auto out = top_of_atmosphere_radiance(zenith_angle_rad);
  for (std::size_t i = 0; i < out.size() && i < transmittance.size(); ++i) out[i] *= transmittance[i];
  return out;
}

double NightSkyFloor::zenith_v_mag_arcsec2() const {
  // The continuous spectrum (lines at their own wavelengths) through the zenith, as calibrated.
  const atmosphere::SpectralTable t = zenith_transmittance_table();
  const double v =
      v_band_mean([&](double l) { return (continuous_radiance(l, true) + continuous_radiance(l, false)) * t(l); });
  double lines = 0.0;
  for (const auto& line : kLines)
    lines += v_band_mean_of_line(line.wavelength_nm, line_radiance_W_m2_sr(line) * t(line.wavelength_nm));
  return v_surface_brightness(v + lines * lines_scale_);
}

double NightSkyFloor::zenith_luminance_cd_m2() const {
  const atmosphere::SpectralTable t = zenith_transmittance_table();
  double y =
      luminance_cd_m2([&](double l) { return (continuous_radiance(l, true) + continuous_radiance(l, false)) * t(l); });
  for (const auto& line : kLines)
    y += 683.0 * atmosphere::photopic_efficiency(line.wavelength_nm) * lines_scale_ * line_radiance_W_m2_sr(line) *
         t(line.wavelength_nm);
  return y;
}

}  // namespace zenith::astro
