#include "atmosphere/reference/sun_disc.h"

#include <algorithm>
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
  for (const LimbDarkening& law : sun.limb_darkening) check_limb_darkening(law, "SunDisc");
  if (!sun.limb_darkening.empty() && sun.angular_radius_rad == 0.0)
    throw std::invalid_argument("SunDisc: a point sun has no limb to darken");
  const Occulter& o = sun.occulter;
  if (!(std::isfinite(o.centre_m.x) && std::isfinite(o.centre_m.y) && std::isfinite(o.centre_m.z)) ||
      !(o.radius_m >= 0.0 && std::isfinite(o.radius_m)))
    throw std::invalid_argument("SunDisc: the occulter needs a finite centre and a finite radius >= 0 m");
  SunDisc v = sun;
  v.direction = sun.direction / len;
  return v;
}

bool occulted(const Occulter& occulter, const Vec3& point_m, const Vec3& direction) {
  if (!(occulter.radius_m > 0.0)) return false;
  const Vec3 to_centre = occulter.centre_m - point_m;
  const double r2 = occulter.radius_m * occulter.radius_m;
  const double along = dot(to_centre, direction);
  const double centre2 = dot(to_centre, to_centre);
  if (centre2 <= r2) return true;       // inside the sphere
  if (along <= 0.0) return false;       // the sphere is behind the point
  return centre2 - along * along < r2;  // the line passes closer to the centre than the radius
}

double limb_weight(const SunDisc& sun, const Vec3& to_sun, std::size_t wavelength) {
  if (sun.limb_darkening.empty()) return 1.0;
  const LimbDarkening& law = sun.limb_darkening.at(wavelength);
  // sin²θ = 1 − cos²θ, from the sampled direction's cosine to the centre.
  const double cos_theta = std::min(1.0, dot(to_sun, sun.direction));
  const double sin_radius = std::sin(sun.angular_radius_rad);
  const double mu2 = 1.0 - (1.0 - cos_theta * cos_theta) / (sin_radius * sin_radius);
  if (!(mu2 > 0.0)) return 0.0;
  return law.intensity(std::sqrt(mu2)) / law.mean_over_centre();
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
