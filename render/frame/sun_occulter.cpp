#include "render/frame/sun_occulter.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"
#include "astro/solar_eclipse.h"
#include "atmosphere/solar_limb_darkening.h"
#include "core/units.h"
#include "render/frame/frame_conditions.h"
#include "scene/local_horizon.h"

namespace zenith::render {

namespace {

/// The eclipse's geometry where the shadow of a sphere of `moon_radius_m` at
/// `moon_centre` (from the centre of `planet`) can reach the air the camera
/// sees: the camera within two penumbra radii (where V̄ reaches 1,
/// astro/moon_shadow.h) plus the air's reach (the camera's horizon distance
/// and the top of the atmosphere's) of the shadow's axis.
std::optional<astro::EclipseGeometry> shadow_on_the_air(const scene::Scene& scene, const scene::Body& planet,
                                                        const glm::dvec3& moon_centre, double moon_radius_m,
                                                        const std::vector<atmosphere::LimbDarkening>& limb,
                                                        double& air_from_axis_penumbrae) {
  if (!planet.atmosphere) return std::nullopt;
  const atmosphere::AtmosphereModel& model = planet.atmosphere->loaded.model;
  const glm::dvec3 camera = scene.camera.position_m - planet.position_m;
  const glm::dvec3 sun = glm::normalize(scene.sun.direction);
  // The camera behind the Moon along the sunlight, and its distance from the shadow's axis.
  const glm::dvec3 from_moon = camera - moon_centre;
  const double behind_m = -glm::dot(from_moon, sun);
  if (behind_m <= 0.0) return std::nullopt;  // the camera is sunward of the Moon
  const double off_axis_m = glm::length(from_moon + behind_m * sun);
  const double r = glm::length(camera), bottom = model.ground_radius_m, top = model.top_radius_m;
  const double reach_m =
      std::sqrt(std::max(0.0, (r - bottom) * (r + bottom))) + std::sqrt(std::max(0.0, (top - bottom) * (top + bottom)));
  const double penumbra_m =
      behind_m * std::tan(scene.sun.angular_radius_rad + std::asin(std::min(1.0, moon_radius_m / behind_m)));
  if (off_axis_m >= 2.0 * penumbra_m + reach_m) return std::nullopt;
  air_from_axis_penumbrae = (off_axis_m - reach_m) / penumbra_m;
  return astro::EclipseGeometry{moon_centre, moon_radius_m, sun, scene.sun.angular_radius_rad, limb};
}

std::vector<atmosphere::LimbDarkening> limb_darkening_laws(const scene::Scene& scene, bool limb_darkening) {
  std::vector<atmosphere::LimbDarkening> limb;  // uniform discs without limb darkening
  for (double nm : scene.wavelengths_nm)
    limb.push_back(limb_darkening ? atmosphere::solar_limb_darkening(nm) : atmosphere::LimbDarkening{});
  return limb;
}

/// A scene of bodies: the airless bodies' shadows on the air of the body with
/// an atmosphere nearest the camera (whose air fills the view, when any does).
SunOcculter shadow_among_bodies(const scene::Scene& scene, bool limb_darkening) {
  SunOcculter out;
  std::optional<std::size_t> planet;
  double nearest_m = 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const scene::Body& b = scene.bodies[i];
    if (!b.atmosphere) continue;
    const double d = glm::length(scene.camera.position_m - b.position_m) - b.atmosphere->loaded.model.top_radius_m;
    if (!planet || d < nearest_m) {
      planet = i;
      nearest_m = d;
    }
  }
  if (!planet) return out;
  const scene::Body& air = scene.bodies[*planet];
  const std::vector<atmosphere::LimbDarkening> limb = limb_darkening_laws(scene, limb_darkening);
  for (const scene::Body& moon : scene.bodies) {
    if (&moon == &air || !shadow_on_air_possible(scene, moon, air)) continue;
    double from_axis = 0.0;
    std::optional<astro::EclipseGeometry> shadow =
        shadow_on_the_air(scene, air, moon.position_m - air.position_m, moon.radius_m, limb, from_axis);
    if (shadow && (!out.shadow || from_axis < out.air_from_axis_penumbrae)) {
      out.shadow = std::move(shadow);
      out.air_from_axis_penumbrae = from_axis;
      out.shadow_planet = *planet;
      out.shadow_caster_is_a_body = true;
    }
  }
  return out;
}

}  // namespace

SunOcculter sun_occulter(const scene::Scene& scene, const FrameSky& sky, bool limb_darkening) {
  if (!scene.sky_clock) return shadow_among_bodies(scene, limb_darkening);
  SunOcculter out;
  const scene::SkyClock& clock = *scene.sky_clock;
  const scene::Body& planet = scene.bodies.at(clock.body);
  const astro::MoonPlace moon = sky.positions().moon();
  const scene::LocalHorizon horizon = scene::local_horizon_at(scene.camera.position_m, planet);
  const glm::dvec3 direction =
      glm::normalize(horizon.direction(moon.horizontal.azimuth_rad, moon.horizontal.altitude_rad));
  const glm::dvec3 sun = glm::normalize(scene.sun.direction);
  // atan2(|a × b|, a · b): accurate for the small angles that matter here.
  const double separation = std::atan2(glm::length(glm::cross(direction, sun)), glm::dot(direction, sun));
  const double r_s = scene.sun.angular_radius_rad, r_m = moon.angular_radius_rad;
  const std::vector<atmosphere::LimbDarkening> limb = limb_darkening_laws(scene, limb_darkening);
  // The Moon placed from the clock's site (its topocentric direction and
  // distance), the site below the camera at its altitude: a camera in orbit
  // is not where the ephemeris looked from, and 400 km of it would move the
  // umbra by as much.
  const glm::dvec3 camera = scene.camera.position_m - planet.position_m;
  const glm::dvec3 site = glm::normalize(camera) * (planet.radius_m + clock.site.altitude_m);
  out.shadow = shadow_on_the_air(scene, planet, site + direction * (moon.distance_km * 1e3),
                                 astro::kMoonRadius_km * 1e3, limb, out.air_from_axis_penumbrae);
  out.shadow_planet = clock.body;
  if (separation >= r_s + r_m) return out;
  out.direction = direction;
  out.angular_radius_rad = r_m;
  out.separation_rad = separation;
  for (const atmosphere::LimbDarkening& law : limb)
    out.uncovered.push_back(1.0 - astro::limb_darkened_obscuration(separation, r_s, r_m, law));
  return out;
}

}  // namespace zenith::render
