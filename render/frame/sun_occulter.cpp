#include "render/frame/sun_occulter.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"
#include "astro/solar_eclipse.h"
#include "scene/local_horizon.h"
#include "scene/sun_disc.h"

namespace zenith::render {

SunOcculter sun_occulter(const scene::Scene& scene, bool limb_darkening) {
  SunOcculter out;
  if (!scene.sky_clock) return out;
  const scene::SkyClock& clock = *scene.sky_clock;
  const astro::MoonPlace moon = astro::SkyPositions(astro::AstroTime::from_utc(clock.time), clock.site).moon();
  const scene::LocalHorizon horizon = scene::local_horizon_at(scene.camera.position_m, scene.bodies.at(clock.body));
  const glm::dvec3 direction =
      glm::normalize(horizon.direction(moon.horizontal.azimuth_rad, moon.horizontal.altitude_rad));
  const glm::dvec3 sun = glm::normalize(scene.sun.direction);
  // atan2(|a × b|, a · b): accurate for the small angles that matter here.
  const double separation = std::atan2(glm::length(glm::cross(direction, sun)), glm::dot(direction, sun));
  const double r_s = scene.sun.angular_radius_rad, r_m = moon.angular_radius_rad;
  if (separation >= r_s + r_m) return out;
  out.direction = direction;
  out.angular_radius_rad = r_m;
  out.separation_rad = separation;
  for (double nm : scene.wavelengths_nm) {
    const double a = limb_darkening ? scene::limb_darkening_exponent(nm) : 0.0;
    out.uncovered.push_back(1.0 - astro::limb_darkened_obscuration(separation, r_s, r_m, a));
  }
  return out;
}

}  // namespace zenith::render
