#include "render/frame/sun_occulter.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"
#include "astro/solar_eclipse.h"
#include "atmosphere/solar_limb_darkening.h"
#include "core/units.h"
#include "scene/local_horizon.h"

namespace zenith::render {

namespace {

/// The eclipse's geometry where the Moon's shadow can reach the air the camera
/// sees: the camera within two penumbra radii (where V̄ reaches 1,
/// astro/moon_shadow.h) plus the air's reach (the camera's horizon distance
/// and the top of the atmosphere's) of the shadow's axis. The Moon is placed
/// from the clock's site (its topocentric direction and distance), the site
/// below the camera at its altitude: a camera in orbit is not where the
/// ephemeris looked from, and 400 km of it would move the umbra by as much.
std::optional<astro::EclipseGeometry> shadow_on_the_air(const scene::Scene& scene, const glm::dvec3& moon_direction,
                                                        double moon_distance_m,
                                                        const std::vector<atmosphere::LimbDarkening>& limb,
                                                        double& air_from_axis_penumbrae) {
  const scene::Body& planet = scene.bodies.at(scene.sky_clock->body);
  if (!planet.atmosphere) return std::nullopt;
  const atmosphere::AtmosphereModel& model = planet.atmosphere->loaded.model;
  const glm::dvec3 camera = scene.camera.position_m - planet.position_m;
  const glm::dvec3 site = glm::normalize(camera) * (planet.radius_m + scene.sky_clock->site.altitude_m);
  const glm::dvec3 moon_centre = site + moon_direction * moon_distance_m;
  const glm::dvec3 sun = glm::normalize(scene.sun.direction);
  // The camera behind the Moon along the sunlight, and its distance from the shadow's axis.
  const glm::dvec3 from_moon = camera - moon_centre;
  const double behind_m = -glm::dot(from_moon, sun);
  if (behind_m <= 0.0) return std::nullopt;  // the camera is sunward of the Moon
  const double off_axis_m = glm::length(from_moon + behind_m * sun);
  const double r = glm::length(camera), bottom = model.ground_radius_m, top = model.top_radius_m;
  const double reach_m =
      std::sqrt(std::max(0.0, (r - bottom) * (r + bottom))) + std::sqrt(std::max(0.0, (top - bottom) * (top + bottom)));
  const double penumbra_m = behind_m * std::tan(scene.sun.angular_radius_rad +
                                                std::asin(std::min(1.0, astro::kMoonRadius_km * 1e3 / behind_m)));
  if (off_axis_m >= 2.0 * penumbra_m + reach_m) return std::nullopt;
  air_from_axis_penumbrae = (off_axis_m - reach_m) / penumbra_m;
  return astro::EclipseGeometry{moon_centre, astro::kMoonRadius_km * 1e3, sun, scene.sun.angular_radius_rad, limb};
}

}  // namespace

SunOcculter sun_occulter(const scene::Scene& scene, const FrameSky& sky, bool limb_darkening) {
  SunOcculter out;
  if (!scene.sky_clock) return out;
  const scene::SkyClock& clock = *scene.sky_clock;
  const astro::MoonPlace moon = sky.positions().moon();
  const scene::LocalHorizon horizon = scene::local_horizon_at(scene.camera.position_m, scene.bodies.at(clock.body));
  const glm::dvec3 direction =
      glm::normalize(horizon.direction(moon.horizontal.azimuth_rad, moon.horizontal.altitude_rad));
  const glm::dvec3 sun = glm::normalize(scene.sun.direction);
  // atan2(|a × b|, a · b): accurate for the small angles that matter here.
  const double separation = std::atan2(glm::length(glm::cross(direction, sun)), glm::dot(direction, sun));
  const double r_s = scene.sun.angular_radius_rad, r_m = moon.angular_radius_rad;
  std::vector<atmosphere::LimbDarkening> limb;  // uniform discs without limb darkening
  for (double nm : scene.wavelengths_nm)
    limb.push_back(limb_darkening ? atmosphere::solar_limb_darkening(nm) : atmosphere::LimbDarkening{});
  out.shadow = shadow_on_the_air(scene, direction, moon.distance_km * 1e3, limb, out.air_from_axis_penumbrae);
  if (separation >= r_s + r_m) return out;
  out.direction = direction;
  out.angular_radius_rad = r_m;
  out.separation_rad = separation;
  for (const atmosphere::LimbDarkening& law : limb)
    out.uncovered.push_back(1.0 - astro::limb_darkened_obscuration(separation, r_s, r_m, law));
  return out;
}

}  // namespace zenith::render
