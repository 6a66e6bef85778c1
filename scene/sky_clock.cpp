#include "scene/sky_clock.h"

#include <glm/geometric.hpp>

#include "core/units.h"
#include "scene/local_horizon.h"
#include "scene/scene.h"

namespace zenith::scene {

EphemerisSun ephemeris_sun(const Scene& scene, const SkyClock& clock, const astro::AstroTime& time,
                           const glm::dvec3& camera_position_m) {
  const astro::SunPlace place = astro::SkyPositions(time, clock.site).sun();
  EphemerisSun sun;
  sun.azimuth_deg = place.horizontal.azimuth_rad / core::kDeg;
  sun.altitude_deg = place.horizontal.altitude_rad / core::kDeg;
  const LocalHorizon horizon = local_horizon_at(camera_position_m, scene.bodies.at(clock.body));
  sun.direction = glm::normalize(horizon.direction(place.horizontal.azimuth_rad, place.horizontal.altitude_rad));
  sun.distance_au = place.distance_au;
  sun.angular_radius_rad = place.angular_radius_rad;
  return sun;
}

}  // namespace zenith::scene
