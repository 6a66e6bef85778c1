#pragma once
// The CPU's 3-vector: GLM's dvec3, the one vector library of scene/, warp/,
// render/ and astro/ too, here for planet-frame geometry in metres
// (planet-centred: the planet's centre is the origin). dot, cross, length and
// normalize are GLM's, also by these names in this namespace.
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace zenith::atmosphere {

using Vec3 = glm::dvec3;
using glm::cross;
using glm::dot;
using glm::length;
using glm::normalize;

/// Unit vector from a zenith angle and an azimuth [rad] in the local frame of a
/// point on the +z axis: z is up (zenith), x is azimuth 0, y is azimuth 90°.
inline Vec3 direction_from_angles(double zenith_rad, double azimuth_rad) {
  const double s = std::sin(zenith_rad);
  return {s * std::cos(azimuth_rad), s * std::sin(azimuth_rad), std::cos(zenith_rad)};
}

}  // namespace zenith::atmosphere
