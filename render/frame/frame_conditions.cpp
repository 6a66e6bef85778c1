#include "render/frame/frame_conditions.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/units.h"

namespace zenith::render {

bool moon_can_eclipse_the_sun(const scene::Scene& scene, bool moon_drawn, bool bodies_shadow) {
  return scene.sky_clock ? moon_drawn : bodies_shadow && airless_shadow_on_air_possible(scene);
}

namespace {
/// Whether `occluder` (a sphere of `occluder_radius_m`) can shadow any part
/// of a sphere of `receiver_radius_m` around `receiver`: the receiver within
/// the penumbra's cone, with a 1 % margin.
bool shadow_can_reach(const scene::Scene& scene, const glm::dvec3& occluder, double occluder_radius_m,
                      const glm::dvec3& receiver, double receiver_radius_m) {
  const glm::dvec3 s = glm::normalize(scene.sun.direction);
  const double tan_alpha = std::tan(std::min(scene.sun.angular_radius_rad, 1.0));
  const glm::dvec3 oc = occluder - receiver;
  const double d = glm::dot(oc, s) + receiver_radius_m;  // largest d over the receiver
  if (d <= 0.0) return false;                            // the occluder is behind the receiver, away from the sun
  const double off_axis = glm::length(oc - glm::dot(oc, s) * s) - receiver_radius_m;
  return off_axis < 1.01 * (occluder_radius_m + d * tan_alpha) + 1.0;
}
}  // namespace

bool eclipses_possible(const scene::Scene& scene) {
  for (const scene::Body& occluder : scene.bodies)
    for (const scene::Body& receiver : scene.bodies)
      if (&occluder != &receiver && shadow_can_reach(scene, occluder.position_m, shadow_casting_radius_m(occluder),
                                                     receiver.position_m, receiver.radius_m))
        return true;
  return false;
}

bool shadow_on_air_possible(const scene::Scene& scene, const scene::Body& occluder, const scene::Body& receiver) {
  if (occluder.atmosphere || !receiver.atmosphere || occluder.radius_m <= 0.0) return false;
  const double top_m = receiver.atmosphere->loaded.model.top_radius_m;
  const double above_air_m = glm::length(occluder.position_m - receiver.position_m) - top_m - occluder.radius_m;
  constexpr double kLeastRadius = 0.316;  // of the sun's: √0.1, a tenth of its disc
  if (above_air_m <= 0.0 || occluder.radius_m < kLeastRadius * scene.sun.angular_radius_rad * above_air_m) return false;
  return shadow_can_reach(scene, occluder.position_m, occluder.radius_m, receiver.position_m, top_m);
}

bool airless_shadow_on_air_possible(const scene::Scene& scene) {
  for (const scene::Body& occluder : scene.bodies)
    for (const scene::Body& receiver : scene.bodies)
      if (&occluder != &receiver && shadow_on_air_possible(scene, occluder, receiver)) return true;
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
