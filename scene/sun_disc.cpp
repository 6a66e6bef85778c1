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

double limb_darkening_exponent(double wavelength_nm) {
  if (!(wavelength_nm >= 100.0 && wavelength_nm <= 10000.0)) {
    std::ostringstream s;
    s << "limb darkening: wavelength " << wavelength_nm << " nm must be in [100, 10000] nm";
    throw std::invalid_argument(s.str());
  }
  // Hestroffer & Magnan (1998): α = −0.023 + 0.292 / λ[µm].
  return -0.023 + 0.292 / (wavelength_nm * 1e-3);
}

double limb_darkening(double mu, double wavelength_nm) {
  const double alpha = limb_darkening_exponent(wavelength_nm);
  if (!(mu > 0.0)) return 0.0;  // the limb, outside the disc, and NaN
  return std::pow(std::min(mu, 1.0), alpha);
}

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
  const double alpha = limb_darkening_exponent(wavelength_nm);
  const double sin_radius = std::sin(angular_radius_rad);
  // L_0 = E (α + 2) / (2π sin²θ_s), derived in sun_disc.h.
  return irradiance_W_m2_nm * (alpha + 2.0) / (2.0 * kPi * sin_radius * sin_radius);
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
  return centre * limb_darkening(disc_mu(angle_from_centre_rad, angular_radius_rad), wavelength_nm);
}

}  // namespace zenith::scene
