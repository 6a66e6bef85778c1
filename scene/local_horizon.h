#pragma once
// The local horizon frame of a point above a body (docs/scenes.md, "Frames and
// conventions"): up, north and east, and the azimuth and elevation of a
// direction in it. Scene files give the sun and the view in it ("sky",
// "look"); the operator console sets the sun by it (docs/operator.md, "Sun").
#include <cstddef>

#include <glm/vec3.hpp>

#include "scene/scene.h"

namespace zenith::scene {

/// An azimuth (from north, clockwise seen from above, i.e. toward east) and
/// an elevation above the horizon plane, in degrees.
struct SkyAngles {
  double azimuth_deg = 0.0;    ///< [0, 360) when computed
  double elevation_deg = 0.0;  ///< [−90, 90]
};

/// Invariant: up, north and east are unit vectors, pairwise perpendicular,
/// with east = north × up (east, north, up is right-handed).
struct LocalHorizon {
  glm::dvec3 up{0, 0, 1}, north{0, 1, 0}, east{1, 0, 0};

  /// The unit vector at `azimuth_rad` and `elevation_rad`:
  /// cos e (cos A · north + sin A · east) + sin e · up.
  glm::dvec3 direction(double azimuth_rad, double elevation_rad) const;
  /// The azimuth and elevation of `direction` (any length > 0), in degrees;
  /// straight up or down (within 1e-12 rad), where the azimuth is undefined, it is 0.
  SkyAngles angles_of(const glm::dvec3& direction) const;
};

/// The local horizon at `point_m` above `body`: up from the body's centre
/// through the point, north the body's north pole (its +z) projected onto the
/// horizon plane; exactly at a pole, its limit along the prime meridian
/// (body −x at the north pole, +x at the south pole). `point_m` must not be
/// the body's centre.
LocalHorizon local_horizon_at(const glm::dvec3& point_m, const Body& body);

}  // namespace zenith::scene
