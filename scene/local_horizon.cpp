#include "scene/local_horizon.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/units.h"

namespace zenith::scene {

using glm::dvec3;

dvec3 LocalHorizon::direction(double azimuth_rad, double elevation_rad) const {
  const dvec3 horizontal = std::cos(azimuth_rad) * north + std::sin(azimuth_rad) * east;
  return std::cos(elevation_rad) * horizontal + std::sin(elevation_rad) * up;
}

SkyAngles LocalHorizon::angles_of(const dvec3& d) const {
  const double n = glm::dot(d, north), e = glm::dot(d, east), u = glm::dot(d, up);
  const double horizontal = std::hypot(n, e);
  SkyAngles a;
  a.elevation_deg = std::atan2(u, horizontal) / core::kDeg;
  // Within rounding of straight up or down the azimuth is noise: 0 there.
  a.azimuth_deg = horizontal > 1e-12 * std::abs(u) ? std::atan2(e, n) / core::kDeg : 0.0;
  if (a.azimuth_deg < 0.0) a.azimuth_deg += 360.0;
  if (a.azimuth_deg >= 360.0) a.azimuth_deg = 0.0;  // −0 and rounding just below 0
  return a;
}

LocalHorizon local_horizon_at(const dvec3& point_m, const Body& body) {
  LocalHorizon h;
  h.up = glm::normalize(point_m - body.position_m);
  const dvec3 pole = body.orientation * dvec3(0, 0, 1);
  const dvec3 north = pole - glm::dot(pole, h.up) * h.up;
  if (glm::length(north) > 1e-12) {
    h.north = glm::normalize(north);
  } else {
    const dvec3 prime = body.orientation * dvec3(1, 0, 0);
    h.north = glm::dot(pole, h.up) > 0.0 ? -prime : prime;
  }
  h.east = glm::cross(h.north, h.up);
  return h;
}

}  // namespace zenith::scene
