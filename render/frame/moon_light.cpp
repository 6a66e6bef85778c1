#include "render/frame/moon_light.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "astro/civil_time.h"
#include "astro/moon_photometry.h"
#include "astro/sky_positions.h"
#include "render/frame/sky_radiance_bound.h"
#include "render/frame/star_pass.h"
#include "render/frame/tile_classification.h"
#include "scene/local_horizon.h"

namespace zenith::render {

bool MoonLight::any() const { return std::find(lit.begin(), lit.end(), true) != lit.end(); }

MoonLight moon_light(const FrameState& frame) {
  MoonLight out;
  const scene::Scene& scene = frame.scene;
  out.lit.assign(frame.passes.size(), false);
  out.bounds.assign(frame.passes.size(), 0.0);
  if (!scene.sky_clock) return out;
  bool any = false;
  for (const AtmospherePass& pass : frame.passes) any = any || pass.gpu != nullptr;
  if (!any) return out;

  // The Moon's place at the sky time (ERFA, topocentric, geometric) in the
  // camera's local horizon, as ephemeris_sun places the Sun.
  const scene::SkyClock& clock = *scene.sky_clock;
  const astro::MoonPlace moon = astro::SkyPositions(astro::AstroTime::from_utc(clock.time), clock.site).moon();
  const scene::LocalHorizon horizon = scene::local_horizon_at(scene.camera.position_m, scene.bodies.at(clock.body));
  out.altitude_rad = moon.horizontal.altitude_rad;
  out.light.direction = glm::normalize(horizon.direction(moon.horizontal.azimuth_rad, moon.horizontal.altitude_rad));
  out.light.angular_radius_rad = moon.angular_radius_rad;
  out.light.irradiance_W_m2_nm = astro::moon_irradiance_W_m2_nm(moon, scene.wavelengths_nm);

  // The test, per atmosphere (seen through T ≤ 1 of those in front):
  // exposure · Σ_λ max_c |w_c(λ)| E_moon(λ) K(λ), K the tables' bound per unit
  // irradiance for the Moon's cosine over the points a pixel reads.
  for (std::size_t a = 0; a < frame.passes.size(); ++a) {
    const AtmospherePass& pass = frame.passes[a];
    if (!pass.gpu) continue;
    const scene::Body& planet = scene.bodies[static_cast<std::size_t>(pass.body)];
    const glm::dvec3 up = glm::normalize(scene.camera.position_m - planet.position_m);
    const ShellInView shell{pass.body, pass.direction_camera, pass.distance_m, pass.top_radius_m, true, false};
    const bool bodies_inside = !bodies_inside_shell(scene, shell).empty();
    const double mu_s_max = source_cosine_bound(glm::dot(up, out.light.direction), pass.distance_m,
                                                pass.gpu->ground_radius_m(), pass.gpu->top_radius_m(), bodies_inside);
    // A camera inside the shell with no other body in it reads the 4D tables at its own radius only.
    const bool at_camera = !bodies_inside && pass.distance_m <= pass.gpu->top_radius_m();
    const std::vector<double> k = pass.gpu->radiance_bound().radiance_per_irradiance(
        mu_s_max,
        at_camera ? std::optional<double>(std::max(pass.distance_m, pass.gpu->ground_radius_m())) : std::nullopt);
    double bound = 0.0;
    for (std::size_t i = 0; i < k.size() && i < frame.rgb_weights.size(); ++i) {
      const auto& w = frame.rgb_weights[i];
      bound += std::max({std::abs(w[0]), std::abs(w[1]), std::abs(w[2])}) * out.light.irradiance_W_m2_nm[i] * k[i];
    }
    out.bounds[a] = bound * scene.camera.exposure;
    out.lit[a] = out.bounds[a] >= kInvisibleDisplayStep;
  }
  return out;
}

}  // namespace zenith::render
