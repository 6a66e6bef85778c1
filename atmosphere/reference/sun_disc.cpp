#include "atmosphere/reference/sun_disc.h"

#include <cmath>
#include <stdexcept>

#include "atmosphere/constants.h"
#include "atmosphere/reference/direction_sampling.h"

namespace zenith::atmosphere::reference {

SunDisc validated(const SunDisc& sun) {
  const double len = length(sun.direction);
  if (!(len > 0.0) || !std::isfinite(len)) throw std::invalid_argument("SunDisc: zero or non-finite direction");
  if (!(sun.angular_radius_rad >= 0.0 && sun.angular_radius_rad < 0.5 * kPi))
    throw std::invalid_argument("SunDisc: angular radius must be in [0, pi/2) rad");
  return SunDisc{sun.direction / len, sun.angular_radius_rad};
}

namespace {
/// 1 − cos α computed as 2 sin²(α/2), without cancellation for small α.
double one_minus_cos(double angle) {
  const double s = std::sin(0.5 * angle);
  return 2.0 * s * s;
}
}  // namespace

double sun_solid_angle_sr(const SunDisc& sun) { return 2.0 * kPi * one_minus_cos(sun.angular_radius_rad); }

Vec3 sample_sun_direction(const SunDisc& sun, double u1, double u2) {
  if (sun.angular_radius_rad == 0.0) return sun.direction;
  const double one_minus_cos_theta = u1 * one_minus_cos(sun.angular_radius_rad);
  const double cos_theta = 1.0 - one_minus_cos_theta;
  const double sin_theta = std::sqrt(std::max(0.0, one_minus_cos_theta * (2.0 - one_minus_cos_theta)));
  const double phi = 2.0 * kPi * u2;
  return Frame::around(sun.direction).to_world(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
}

double sun_sample_weight(const SunDisc& sun) { return 2.0 / (1.0 + std::cos(sun.angular_radius_rad)); }

}  // namespace zenith::atmosphere::reference
