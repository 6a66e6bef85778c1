#include "atmosphere/reference/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace zenith::atmosphere::reference {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}

Ray::Ray(const Vec3& origin_m, const Vec3& direction) : origin_m_(origin_m) {
  const double len = length(direction);
  if (!(len > 0.0) || !std::isfinite(len)) throw std::invalid_argument("Ray: zero or non-finite direction");
  direction_ = direction / len;
  perigee_t_m_ = -dot(origin_m_, direction_);
  // origin − (origin·d) d: for a distant origin each component cancels to the
  // perigee's size with an absolute error of ~ulp(|origin|) (1e-3 m at 40 AU).
  perigee_point_m_ = origin_m_ + perigee_t_m_ * direction_;
  impact_parameter_m_ = length(perigee_point_m_);
}

double Ray::radius_at(double t_m) const {
  const double u = t_m - perigee_t_m_;
  return std::sqrt(impact_parameter_m_ * impact_parameter_m_ + u * u);
}

double Ray::cos_zenith_at(double t_m) const {
  const double r = radius_at(t_m);
  return r > 0.0 ? (t_m - perigee_t_m_) / r : 1.0;
}

std::optional<Ray::SphereCrossings> Ray::sphere_crossings(double radius_m) const {
  const double p = impact_parameter_m_;
  if (!(p < radius_m)) return std::nullopt;
  const double half_chord = std::sqrt((radius_m - p) * (radius_m + p));
  return SphereCrossings{perigee_t_m_ - half_chord, perigee_t_m_ + half_chord};
}

AtmosphereInterval atmosphere_interval(const Ray& ray, double ground_radius_m, double top_radius_m, double t_min_m) {
  AtmosphereInterval interval;
  const auto top = ray.sphere_crossings(top_radius_m);
  if (!top || top->exit_t_m <= t_min_m) return interval;  // misses the shell, or already left it
  interval.begin_t_m = std::max(t_min_m, top->entry_t_m);
  interval.end_t_m = top->exit_t_m;
  if (interval.begin_t_m < ray.perigee_t_m()) {  // still moving toward the centre
    if (const auto ground = ray.sphere_crossings(ground_radius_m)) {
      interval.end_t_m = std::max(interval.begin_t_m, ground->entry_t_m);
      interval.ends_on_ground = true;
    }
  }
  interval.intersects = true;
  return interval;
}

bool ray_hits_ground(double r_m, double mu, double ground_radius_m) {
  if (!(mu < 0.0)) return false;
  const double R = ground_radius_m;
  return r_m * r_m * mu * mu - (r_m - R) * (r_m + R) > 0.0;
}

double distance_to_ground_m(double r_m, double mu, double ground_radius_m) {
  if (!ray_hits_ground(r_m, mu, ground_radius_m)) return kInfinity;
  const double R = ground_radius_m;
  const double c = (r_m - R) * (r_m + R);
  const double discriminant = r_m * r_m * mu * mu - c;
  return std::max(0.0, c / (-r_m * mu + std::sqrt(discriminant)));
}

double distance_to_top_of_atmosphere_m(double r_m, double mu, double top_radius_m) {
  const double Rt = top_radius_m;
  const double c = (r_m - Rt) * (r_m + Rt);  // ≤ 0 inside
  const double discriminant = r_m * r_m * mu * mu - c;
  if (discriminant < 0.0 || (c > 0.0 && mu >= 0.0)) return kInfinity;
  return -r_m * mu + std::sqrt(discriminant);
}

double distance_to_atmosphere_entry_m(double r_m, double mu, double top_radius_m) {
  const double Rt = top_radius_m;
  if (r_m <= Rt) return 0.0;
  const double c = (r_m - Rt) * (r_m + Rt);
  const double discriminant = r_m * r_m * mu * mu - c;
  if (!(mu < 0.0) || discriminant < 0.0) return kInfinity;
  return c / (-r_m * mu + std::sqrt(discriminant));
}

std::vector<double> planet_shadow_crossings_t_m(const Ray& ray, const Vec3& sun_direction, double ground_radius_m,
                                                double t_min_m) {
  // Components perpendicular to the sun direction s. With x = P + u d (P the
  // perigee point, u = t − t_c): |P⊥ + u d⊥|² = R²  ⇔  a u² + 2 b u + c = 0.
  const Vec3& s = sun_direction;
  const Vec3 P = ray.perigee_point_m();
  const Vec3& d = ray.direction();
  const Vec3 P_perp = P - dot(P, s) * s;
  const Vec3 d_perp = d - dot(d, s) * s;
  const double a = dot(d_perp, d_perp);
  const double b = dot(P_perp, d_perp);
  const double c = (length(P_perp) - ground_radius_m) * (length(P_perp) + ground_radius_m);
  std::vector<double> crossings;
  if (!(a > 0.0)) return crossings;  // ray parallel to the sun: never crosses the cylinder wall
  const double discriminant = b * b - a * c;
  if (!(discriminant > 0.0)) return crossings;
  // Cancellation-free roots: q = −(b + sign(b)√D); u1 = q/a, u2 = c/q.
  const double q = -(b + std::copysign(std::sqrt(discriminant), b));
  const double roots[2] = {q / a, c / q};  // q ≠ 0 since D > 0
  for (double u : roots) {
    const double t = ray.perigee_t_m() + u;
    if (t > t_min_m && dot(P + u * d, s) < 0.0) crossings.push_back(t);
  }
  std::sort(crossings.begin(), crossings.end());
  return crossings;
}

std::vector<double> sphere_crossings_t_m(const Ray& ray, const std::vector<double>& radii_m, double t_min_m,
                                         double t_max_m) {
  std::vector<double> crossings;
  for (double radius : radii_m) {
    if (const auto x = ray.sphere_crossings(radius)) {
      for (double t : {x->entry_t_m, x->exit_t_m})
        if (t > t_min_m && t < t_max_m) crossings.push_back(t);
    }
  }
  std::sort(crossings.begin(), crossings.end());
  return crossings;
}

}  // namespace zenith::atmosphere::reference
