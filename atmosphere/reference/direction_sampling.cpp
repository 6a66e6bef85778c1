#include "atmosphere/reference/direction_sampling.h"

#include <algorithm>
#include <cmath>

#include "atmosphere/constants.h"

namespace zenith::atmosphere::reference {

Frame Frame::around(const Vec3& w) {
  const double sign = std::copysign(1.0, w.z);
  const double a = -1.0 / (sign + w.z);
  const double b = w.x * w.y * a;
  Frame f;
  f.u = {1.0 + sign * w.x * w.x * a, sign * b, -sign * w.x};
  f.v = {b, sign + w.y * w.y * a, -w.y};
  f.w = w;
  return f;
}

Vec3 direction_with_cosine(const Vec3& axis, double cos_theta, double u) {
  const double c = std::clamp(cos_theta, -1.0, 1.0);
  const double s = std::sqrt(std::max(0.0, (1.0 - c) * (1.0 + c)));
  const double phi = 2.0 * kPi * u;
  return Frame::around(axis).to_world(s * std::cos(phi), s * std::sin(phi), c);
}

Vec3 sample_cosine_hemisphere(const Vec3& normal, double u1, double u2) {
  const double radius = std::sqrt(u1);
  const double phi = 2.0 * kPi * u2;
  return Frame::around(normal).to_world(radius * std::cos(phi), radius * std::sin(phi), std::sqrt(1.0 - u1));
}

}  // namespace zenith::atmosphere::reference
