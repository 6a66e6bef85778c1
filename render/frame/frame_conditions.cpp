#include "render/frame/frame_conditions.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/units.h"

namespace zenith::render {

bool moon_can_eclipse_the_sun(const scene::Scene& scene, bool moon_drawn) {
  return moon_drawn && scene.sky_clock.has_value();
}

bool eclipses_possible(const scene::Scene& scene) {
  const glm::dvec3 s = glm::normalize(scene.sun.direction);
  const double tan_alpha = std::tan(std::min(scene.sun.angular_radius_rad, 1.0));
  for (const scene::Body& occluder : scene.bodies)
    for (const scene::Body& receiver : scene.bodies) {
      if (&occluder == &receiver) continue;
      const glm::dvec3 oc = occluder.position_m - receiver.position_m;
      const double d = glm::dot(oc, s) + receiver.radius_m;  // largest d over the receiver
      if (d <= 0.0) continue;                                // the occluder is behind the receiver, away from the sun
      const double off_axis = glm::length(oc - glm::dot(oc, s) * s) - receiver.radius_m;
      if (off_axis < 1.01 * (shadow_casting_radius_m(occluder) + d * tan_alpha) + 1.0) return true;
    }
  return false;
}

double shadow_casting_radius_m(const scene::Body& body) {
  return body.atmosphere ? body.atmosphere->loaded.model.top_radius_m : body.radius_m;
}

bool albedo_at_full_resolution(const scene::Scene& scene, double pixel_angle, int map_width) {
  for (const scene::Body& body : scene.bodies) {
    const double D = glm::length(body.position_m - scene.camera.position_m), R = body.radius_m;
    const double farthest = std::sqrt(std::max((D - R) * (D + R), 0.0));
    const double texel = 2.0 * core::kPi * R / std::max(map_width, 1);
    if (20.0 * pixel_angle * farthest > 0.99 * texel) return false;
  }
  return true;
}

bool sky_view_accurate(double r, double ground_radius, double top_radius, double mu_s) {
  const double height = (r - ground_radius) / (top_radius - ground_radius);
  const double mu_horizon = -std::sqrt(std::max(0.0, 1.0 - (ground_radius / r) * (ground_radius / r)));
  return height <= 0.02 || (height <= 0.2 && mu_s > mu_horizon);
}

}  // namespace zenith::render
