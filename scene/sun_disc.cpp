#include "scene/sun_disc.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/units.h"

namespace zenith::scene {
namespace {

using core::kPi;

void check_angular_radius(double angular_radius_rad) {
  if (!(angular_radius_rad > 0.0 && angular_radius_rad < 0.5 * kPi)) {
    std::ostringstream s;
    s << "sun disc: angular radius " << angular_radius_rad << " rad must be in (0, pi/2)";
    throw std::invalid_argument(s.str());
  }
}

}  // namespace

double disc_mu(double angle_from_centre_rad, double angular_radius_rad) {
  check_angular_radius(angular_radius_rad);
  const double theta = std::abs(angle_from_centre_rad);
  if (!(theta < angular_radius_rad)) return 0.0;
  const double ratio = std::sin(theta) / std::sin(angular_radius_rad);
  return std::sqrt(std::max(0.0, 1.0 - ratio * ratio));
}

double disc_centre_radiance(double irradiance_W_m2_nm, double angular_radius_rad, double wavelength_nm) {
  check_angular_radius(angular_radius_rad);
  if (!(irradiance_W_m2_nm >= 0.0 && std::isfinite(irradiance_W_m2_nm))) {
    std::ostringstream s;
    s << "sun disc: irradiance " << irradiance_W_m2_nm << " W m^-2 nm^-1 must be finite and >= 0";
    throw std::invalid_argument(s.str());
  }
  const double mean_over_centre = atmosphere::solar_limb_darkening(wavelength_nm).mean_over_centre();
  const double sin_radius = std::sin(angular_radius_rad);
  // L_0 = E / (π sin²θ_s m), derived in sun_disc.h.
  return irradiance_W_m2_nm / (kPi * sin_radius * sin_radius * mean_over_centre);
}

double uniform_disc_radiance(double irradiance_W_m2_nm, double angular_radius_rad) {
  check_angular_radius(angular_radius_rad);
  if (!(irradiance_W_m2_nm >= 0.0 && std::isfinite(irradiance_W_m2_nm))) {
    std::ostringstream s;
    s << "sun disc: irradiance " << irradiance_W_m2_nm << " W m^-2 nm^-1 must be finite and >= 0";
    throw std::invalid_argument(s.str());
  }
  const double sin_radius = std::sin(angular_radius_rad);
  // ∫ L cos θ dΩ over the cap = L π sin²θs.
  return irradiance_W_m2_nm / (kPi * sin_radius * sin_radius);
}

double disc_radiance(double irradiance_W_m2_nm, double angular_radius_rad, double wavelength_nm,
                     double angle_from_centre_rad) {
  const double centre = disc_centre_radiance(irradiance_W_m2_nm, angular_radius_rad, wavelength_nm);
  // Outside the disc nothing: the law itself keeps a_0 > 0 at the limb.
  if (!(std::abs(angle_from_centre_rad) < angular_radius_rad)) return 0.0;
  return centre *
         atmosphere::solar_limb_darkening(wavelength_nm).intensity(disc_mu(angle_from_centre_rad, angular_radius_rad));
}

}  // namespace zenith::scene
