#include "astro/moon_orientation.h"

#include <erfa.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/units.h"

namespace zenith::astro {
namespace {

/// r^T v: a vector of the rotated frame back on GCRS axes.
glm::dvec3 transposed_times(const double r[3][3], const glm::dvec3& v) {
  glm::dvec3 out{};
  for (int i = 0; i < 3; ++i) out[i] = r[0][i] * v[0] + r[1][i] * v[1] + r[2][i] * v[2];
  return out;
}

}  // namespace

MoonAxes moon_axes_gcrs(const JulianDate& tt) {
  const double t = ((tt.day1 - 2451545.0) + tt.day2) / 36525.0;  // Julian centuries TT from J2000.0
  const double node = eraFaom03(t);                              // Ω
  const double f = eraFaf03(t);                                  // F = L − Ω
  const double i = kLunarEquatorInclination_deg * core::kDeg;
  // On the mean ecliptic and equinox of date: e1 toward longitude Ω (the lunar
  // equator's descending node), z the pole at longitude Ω + 90°, latitude 90° − I,
  // e2 = z × e1 90° ahead along the lunar equator (the direction of rotation).
  const glm::dvec3 e1{std::cos(node), std::sin(node), 0.0};
  const glm::dvec3 z{-std::sin(i) * std::sin(node), std::sin(i) * std::cos(node), std::cos(i)};
  const glm::dvec3 e2 = glm::cross(z, e1);
  // The prime meridian faces the mean Earth: −(cos F e1 + sin F e2).
  const glm::dvec3 x{-(std::cos(f) * e1[0] + std::sin(f) * e2[0]), -(std::cos(f) * e1[1] + std::sin(f) * e2[1]),
                     -(std::cos(f) * e1[2] + std::sin(f) * e2[2])};
  double rm[3][3];
  eraEcm06(tt.day1, tt.day2, rm);  // GCRS (ICRS axes) → mean ecliptic of date
  MoonAxes axes;
  axes.x = transposed_times(rm, x);
  axes.z = transposed_times(rm, z);
  axes.y = glm::cross(axes.z, axes.x);
  return axes;
}

Selenographic selenographic(const MoonAxes& axes, const glm::dvec3& v) {
  const glm::dvec3 u = glm::normalize(v);
  return {std::atan2(glm::dot(u, axes.y), glm::dot(u, axes.x)), std::asin(std::clamp(glm::dot(u, axes.z), -1.0, 1.0))};
}

MoonOrientation moon_orientation(const SkyPositions& sky, bool geocentric) {
  const JulianDate& tt = sky.time().tt();
  const SkyPositions::MoonVectors v = sky.moon_vectors(geocentric);
  MoonOrientation o;
  o.axes = moon_axes_gcrs(tt);
  const glm::dvec3& u = v.moon_from_observer_au;
  o.observer = selenographic(o.axes, -u);
  o.sun = selenographic(o.axes, v.sun_from_moon_au);
  // P: the axis on the observer's sky, against the true pole of date (the CIP).
  double npb[3][3];
  eraPnm06a(tt.day1, tt.day2, npb);
  const glm::dvec3 pole{npb[2][0], npb[2][1], npb[2][2]};
  const glm::dvec3 los = glm::normalize(u);
  const glm::dvec3 east = glm::normalize(glm::cross(pole, los));
  const glm::dvec3 north = glm::cross(los, east);
  o.axis_position_angle_rad = eraAnp(std::atan2(glm::dot(o.axes.z, east), glm::dot(o.axes.z, north)));
  return o;
}

}  // namespace zenith::astro
