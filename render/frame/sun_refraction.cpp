#include "render/frame/sun_refraction.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/units.h"

namespace zenith::render {
namespace {

/// `d` turned about the horizontal axis to altitude `altitude_rad` in its own
/// vertical plane (`up` the vertical); `d` itself where it is vertical.
glm::dvec3 at_altitude(const glm::dvec3& d, const glm::dvec3& up, double altitude_rad) {
  const glm::dvec3 level = d - glm::dot(d, up) * up;
  const double length = glm::length(level);
  if (length < 1e-12) return d;
  return level / length * std::cos(altitude_rad) + up * std::sin(altitude_rad);
}

}  // namespace

SunDiscLift sun_disc_lift(const scene::Scene& scene, double reach_rad, RefractionCache& refractions) {
  SunDiscLift out;
  const scene::Body* air = nullptr;
  for (const scene::Body& b : scene.bodies)
    if (b.atmosphere && glm::length(scene.camera.position_m - b.position_m) < b.atmosphere->loaded.model.top_radius_m)
      air = &b;
  if (!air) return out;
  const glm::dvec3 from_centre = scene.camera.position_m - air->position_m;
  const astro::Refraction* refraction =
      refractions.get(*air->atmosphere, glm::length(from_centre) - air->atmosphere->loaded.model.ground_radius_m);
  if (!refraction) return out;

  out.active = true;
  out.up = glm::normalize(from_centre);
  const glm::dvec3 sun = glm::normalize(scene.sun.direction);
  const double true_altitude = std::asin(std::clamp(glm::dot(sun, out.up), -1.0, 1.0));
  const double apparent = refraction->apparent_from_true_rad(true_altitude);
  out.apparent_sun = glm::normalize(at_altitude(sun, out.up, apparent));
  // The disc's points appear within its reach of the apparent centre (R falls
  // with altitude: the lift only brings the limbs closer), one entry's margin.
  const double half = std::min(reach_rad, 0.5 * core::kPi) * 1.05 + 1e-5;
  out.step_rad = 2.0 * half / (kSunLiftSamples - 1);
  out.first_altitude_rad = apparent - half;
  for (int i = 0; i < kSunLiftSamples; ++i)
    out.lift_rad[static_cast<std::size_t>(i)] =
        static_cast<float>(refraction->at_apparent_rad(out.first_altitude_rad + i * out.step_rad));
  return out;
}

}  // namespace zenith::render
