#include "astro/scintillation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/units.h"

namespace zenith::astro {

namespace {

constexpr double kScaleHeight_m = 8000.0;  // H of Young's altitude factor

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// (0, 1]: the top 53 bits of a 64-bit hash, never 0 (log below).
double unit_interval(std::uint64_t h) { return (double(h >> 11) + 1.0) * 0x1.0p-53; }

}  // namespace

double scintillation_variance_per_cubed_air_mass(const ScintillationOptions& o, double observer_altitude_m,
                                                 double ground_refractivity, double wavelength_nm) {
  const double fresnel_m = std::sqrt(wavelength_nm * 1e-9 * o.turbulence_height_m);
  const double aperture_m = std::max(o.pupil_mm * 1e-3, fresnel_m);
  const double medium = ground_refractivity / kEarthGroundRefractivity550;
  return 1e-5 * o.c_y * o.c_y * std::pow(aperture_m, -4.0 / 3.0) / o.integration_s *
         std::exp(-2.0 * observer_altitude_m / kScaleHeight_m) * medium * medium;
}

double scintillation_variance_at(double per_cubed_air_mass, double air_mass) {
  return std::clamp(per_cubed_air_mass * (air_mass * air_mass * air_mass), 0.0, 1.0);
}

double scintillation_variance(const ScintillationOptions& o, double air_mass, double observer_altitude_m,
                              double ground_refractivity, double wavelength_nm) {
  if (!(air_mass >= 1.0)) throw std::invalid_argument("scintillation: air mass " + std::to_string(air_mass) + " < 1");
  return scintillation_variance_at(
      scintillation_variance_per_cubed_air_mass(o, observer_altitude_m, ground_refractivity, wavelength_nm), air_mass);
}

double scintillation_normal(std::uint64_t star, std::int64_t interval) {
  const std::uint64_t h1 = splitmix64(star * 0x632BE59BD9B4E019ull ^ splitmix64(std::uint64_t(interval)));
  const std::uint64_t h2 = splitmix64(h1);
  // Box–Muller: √(−2 ln u1) cos(2π u2).
  return std::sqrt(-2.0 * std::log(unit_interval(h1))) * std::cos(2.0 * core::kPi * unit_interval(h2));
}

double scintillation_log_sigma(double variance) { return std::sqrt(std::log1p(std::max(0.0, variance))); }

double scintillation_factor_of_log_sigma(double s, double g) { return std::exp(s * g - 0.5 * s * s); }

double scintillation_factor(double variance, double g) {
  return scintillation_factor_of_log_sigma(scintillation_log_sigma(variance), g);
}

}  // namespace zenith::astro
