#pragma once
// The night sky's own light seen from a camera inside an atmosphere, as a
// table against the view ray's cosine μ to the camera's up
// (shaders/render/night_sky.comp reads it): the natural floor
// (astro/night_sky_floor.h: airglow with van Rhijn's brightening, zodiacal
// light and starlight, given above the atmosphere) through the line of
// sight's transmittance from the atmosphere's own table, plus the glow of
// light pollution (astro/light_pollution.h, already through the air), in
// linear sRGB × exposure. Entry j at t = j/(n − 1) is at μ = μh + (1 − μh) t²,
// μh the ground's horizon from the camera: the samples crowd toward the
// horizon, where van Rhijn's factor and the air mass change fastest. No GL.
#include <array>
#include <vector>

#include <glm/vec3.hpp>

#include "astro/light_pollution.h"
#include "astro/night_sky_floor.h"
#include "render/night/star_placement.h"

namespace zenith::render {

struct NightSkyTable {
  glm::dvec3 up{0, 0, 1};                 ///< world frame, from the planet's centre through the camera
  double horizon_mu = 0.0;                ///< μh = −√(1 − (R/r)²)
  std::vector<std::array<float, 4>> rgb;  ///< (r, g, b, 0) × exposure per entry
  std::array<double, 3> largest{};        ///< per channel, the largest |value| of the table
};

/// The table for a camera at `camera_m` inside `atmosphere`; `floor` and
/// `glow` may be null (not drawn). `entries` ≥ 2.
NightSkyTable night_sky_table(const StarAtmosphere& atmosphere, const glm::dvec3& camera_m,
                              const astro::NightSkyFloor* floor, const astro::LightPollution* glow,
                              const std::vector<std::array<double, 3>>& rgb_weights, double exposure,
                              int entries = 256);

}  // namespace zenith::render
