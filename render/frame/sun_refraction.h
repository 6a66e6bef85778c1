#pragma once
// The sun's disc where the eye sees it (docs/night-sky.md,
// "Refraction"): air bends the light of a low sun upward, so its disc is drawn
// higher than its geometric place — at the horizon by about 0.6° on the Earth,
// more than its own diameter — and flattened, because its lower limb is lifted
// more than its upper. The precomputed tables light the scene from the
// geometric direction (their rays are straight, as the paper's); only the
// drawn disc is refracted, as the star pass refracts the stars.
//
// How the disc is drawn refracted (sun_disc.glsl): a pixel's ray, arriving at
// apparent altitude h, came from true altitude h − R(h), R the refraction of
// the model's own air (astro/refraction.h) at the camera's altitude. The
// shader turns the ray down by R(h) in its vertical plane and asks whether
// that direction falls on the geometric disc; this moves the disc up by
// R(h_sun) and flattens it by 1 − dR/dh. R(h) reaches the shader as a table
// over the apparent altitudes the disc can cover (its reach and a margin),
// kSunLiftSamples entries, linearly interpolated: with the reach of a resolved
// disc (under 0.6°) the spacing is under 0.04° and the interpolation error
// under 0.01″ at the horizon, where R'' is largest (about 4′/deg²).
//
// Applied when the camera is inside a body's atmosphere that refracts (its
// ground refractivity is positive), for the camera's own altitude. Not
// modelled: the bending of the sun seen through a limb from space, the
// disc's colour fringes (dispersion; R at 550 nm for every wavelength, as the
// stars), and the longer air path of the bent ray (the disc is dimmed by the
// apparent ray's transmittance).
#include <array>

#include <glm/vec3.hpp>

#include "render/frame/refraction_cache.h"
#include "scene/scene.h"

namespace zenith::render {

/// Entries of sun_disc.glsl's sun_lift_rad[] (the same number there).
inline constexpr int kSunLiftSamples = 32;

/// What sun_disc.glsl needs to draw the disc refracted; `active` false: straight rays.
struct SunDiscLift {
  bool active = false;
  glm::dvec3 up{0.0, 0.0, 1.0};                   ///< the camera's vertical (away from the body's centre), world
  glm::dvec3 apparent_sun{0.0};                   ///< where the disc's centre is seen, world, unit
  double first_altitude_rad = 0.0;                ///< apparent altitude of lift_rad[0]
  double step_rad = 0.0;                          ///< between entries
  std::array<float, kSunLiftSamples> lift_rad{};  ///< R at those apparent altitudes
};

/// The lift for a frame of `scene` whose sun is drawn within `reach_rad` of
/// its centre (render/frame/frame_constants.h sun_reach_rad), from the air's
/// refraction kept in `refractions` (shared with the star pass). Inactive when
/// the camera is in no atmosphere, or its air does not refract.
SunDiscLift sun_disc_lift(const scene::Scene& scene, double reach_rad, RefractionCache& refractions);

}  // namespace zenith::render
