#include "validate/moonlit_sky.h"

#include <cmath>
#include <stdexcept>

#include "core/units.h"

namespace zenith::validate {
namespace {

double ks_air_mass(double zenith_deg) {
  const double s = std::sin(zenith_deg * core::kDeg);
  return 1.0 / std::sqrt(1.0 - 0.96 * s * s);
}

}  // namespace

double krisciunas_schaefer_moon_nL(double phase_angle_deg, double separation_deg, double moon_zenith_deg,
                                   double sky_zenith_deg, double k_v) {
  if (!(separation_deg > 10.0 && separation_deg <= 180.0))
    throw std::invalid_argument("Krisciunas & Schaefer's f(rho) (eq. 21) holds for separations above 10 deg");
  const double a = std::abs(phase_angle_deg);
  const double moon_ft_cd = std::pow(10.0, -0.4 * (3.84 + 0.026 * a + 4e-9 * a * a * a * a));
  const double c = std::cos(separation_deg * core::kDeg);
  const double f = std::pow(10.0, 5.36) * (1.06 + c * c) + std::pow(10.0, 6.15 - separation_deg / 40.0);
  return f * moon_ft_cd * std::pow(10.0, -0.4 * k_v * ks_air_mass(moon_zenith_deg)) *
         (1.0 - std::pow(10.0, -0.4 * k_v * ks_air_mass(sky_zenith_deg)));
}

double v_mag_arcsec2_from_nanolamberts(double nanolamberts) {
  return (20.7233 - std::log(nanolamberts / 34.08)) / 0.92104;
}

}  // namespace zenith::validate
