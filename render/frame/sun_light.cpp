#include "render/frame/sun_light.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

#include "atmosphere/lut/sky_radiance_bound.h"
#include "render/frame/tile_classification.h"

namespace zenith::render {

double light_display_bound(const FrameInProgress& frame, const AtmospherePass& pass, const glm::dvec3& direction,
                           const std::vector<double>& irradiance_W_m2_nm) {
  if (!pass.gpu) return 0.0;
  const scene::Scene& scene = frame.scene;
  const scene::Body& planet = scene.bodies[static_cast<std::size_t>(pass.body)];
  const glm::dvec3 up = glm::normalize(scene.camera.position_m - planet.position_m);
  const ShellInView shell{pass.body, pass.direction_camera, pass.distance_m, pass.top_radius_m, true, false};
  const bool bodies_inside = !bodies_inside_shell(scene, shell).empty();
  const double mu_s_max = atmosphere::lut::source_cosine_bound(
      glm::dot(up, direction), pass.distance_m, pass.gpu->ground_radius_m(), pass.gpu->top_radius_m(), bodies_inside);
  // A camera inside the shell with no other body in it reads the 4D tables at its own radius only.
  const bool at_camera = !bodies_inside && pass.distance_m <= pass.gpu->top_radius_m();
  const std::vector<double> k = pass.gpu->radiance_bound().radiance_per_irradiance(
      mu_s_max,
      at_camera ? std::optional<double>(std::max(pass.distance_m, pass.gpu->ground_radius_m())) : std::nullopt);
  // exposure · Σ_λ max_c |w_c(λ)| E(λ) K(λ)
  double bound = 0.0;
  for (std::size_t i = 0; i < k.size() && i < frame.rgb_weights.size() && i < irradiance_W_m2_nm.size(); ++i) {
    const auto& w = frame.rgb_weights[i];
    bound += std::max({std::abs(w[0]), std::abs(w[1]), std::abs(w[2])}) * irradiance_W_m2_nm[i] * k[i];
  }
  return bound * scene.camera.exposure;
}

std::vector<double> sunlight_bounds(const FrameInProgress& frame) {
  std::vector<double> out(frame.passes.size(), 0.0);
  for (std::size_t a = 0; a < frame.passes.size(); ++a)
    out[a] = light_display_bound(frame, frame.passes[a], frame.sun, frame.scene.sun.irradiance_W_m2_nm);
  return out;
}

}  // namespace zenith::render
