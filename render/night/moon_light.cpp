#include "render/night/moon_light.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "astro/civil_time.h"
#include "astro/moon_photometry.h"
#include "astro/sky_positions.h"
#include "render/frame/sun_light.h"
#include "render/night/moon_in_shadow.h"
#include "render/night/star_pass.h"
#include "scene/local_horizon.h"

namespace zenith::render {

bool MoonLight::any() const { return std::find(lit.begin(), lit.end(), true) != lit.end(); }

MoonLight moon_light(const FrameInProgress& frame, const MoonInShadow* moon_shadow) {
  MoonLight out;
  out.light.source = FrameLight::Source::moon;
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
  const astro::MoonPlace moon = frame.sky.positions().moon();
  const scene::LocalHorizon horizon = scene::local_horizon_at(scene.camera.position_m, scene.bodies.at(clock.body));
  out.altitude_rad = moon.horizontal.altitude_rad;
  out.light.direction = glm::normalize(horizon.direction(moon.horizontal.azimuth_rad, moon.horizontal.altitude_rad));
  out.light.angular_radius_rad = moon.angular_radius_rad;
  out.light.irradiance_W_m2_nm = astro::moon_irradiance_W_m2_nm(moon, scene.wavelengths_nm);
  if (moon_shadow && moon_shadow->shadowed())  // a lunar eclipse: the face's light left
    for (std::size_t k = 0; k < out.light.irradiance_W_m2_nm.size(); ++k)
      out.light.irradiance_W_m2_nm[k] *= moon_shadow->face()[k];

  // The test, per atmosphere (seen through T ≤ 1 of those in front):
  // exposure · Σ_λ max_c |w_c(λ)| E_moon(λ) K(λ), K the tables' bound per unit
  // irradiance for the Moon's cosine over the points a pixel reads.
  for (std::size_t a = 0; a < frame.passes.size(); ++a) {
    if (!frame.passes[a].gpu) continue;
    out.bounds[a] = light_display_bound(frame, frame.passes[a], out.light.direction, out.light.irradiance_W_m2_nm);
    out.lit[a] = out.bounds[a] >= kInvisibleDisplayStep;
  }
  return out;
}

}  // namespace zenith::render
