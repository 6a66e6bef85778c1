#pragma once
// The refraction of the air the camera looks through (astro/refraction.h: a
// 512-entry table by quadrature, milliseconds to build), kept while the
// atmosphere and the camera's altitude to the metre stay the same, and shared
// by the passes that refract what they draw: the star pass (stars and the
// Moon, render/night/star_pass.h) and the Sun's disc
// (render/frame/sun_refraction.h) — one table per camera altitude for both.
#include <memory>
#include <string>

#include "astro/refraction.h"
#include "scene/scene.h"

namespace zenith::render {

class RefractionCache {
 public:
  /// The refraction of `air` (around a body of ground radius `air.loaded.model.ground_radius_m`)
  /// for a camera `altitude_m` above its ground, at 550 nm. Null where nothing
  /// is refracted: the camera at or above the atmosphere's top, a gas with no
  /// refractivity (no Rayleigh scattering), or one dense enough to trap
  /// horizontal rays above the camera (astro::ducting_altitude_m; warned once).
  const astro::Refraction* get(const scene::BodyAtmosphere& air, double altitude_m);

 private:
  std::string key_;
  std::unique_ptr<astro::Refraction> refraction_;
};

}  // namespace zenith::render
