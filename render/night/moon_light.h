#pragma once
// The Moon as the atmosphere passes' second light
// (docs/night-sky.md, "Moonlight"). The precomputed tables are radiance per unit
// irradiance of a source at infinity, linear in it, so the sky and the ground
// lit by the Moon are the same passes evaluated with the Moon's direction and
// scaled by its spectral irradiance at the top of the atmosphere
// (astro::moon_irradiance_W_m2_nm: sunlight reflected by the regolith, redder
// than the Sun, by its phase): the renderer runs each atmosphere's passes over
// the band's tiles a second time with this light and adds them to what the
// sun's drew (render/renderer.cpp; the Moon's disc itself is night_sky.comp's).
//
// Skipped by its own test, as the star pass: when the Moon's light, bounded
// from the tables (atmosphere/lut/sky_radiance_bound.h) for the Moon's cosine at
// every point the pixels read, times the frame's exposure and the colour
// weights, could not reach half an 8-bit code step at black
// (kInvisibleDisplayStep), no moonlight pass runs and the frame is the same
// bit for bit: any daylight exposure, and a Moon so far below the horizon that
// the tables' twilight from it is negligible (read as the sun's twilight is).
// Decided per atmosphere, each against half a step on its own.
#include <cstddef>
#include <vector>

#include "render/frame/frame_in_progress.h"

namespace zenith::render {

class MoonInShadow;  // render/night/moon_in_shadow.h

/// The frame's Moon as a light and the test's outcome.
struct MoonLight {
  FrameLight light;            ///< the Moon: direction (world, geometric), angular radius, irradiance at the top
                               ///< of the atmosphere
  std::vector<bool> lit;       ///< per frame.passes: that atmosphere's moonlight passes run
  std::vector<double> bounds;  ///< per frame.passes: the largest linear display value its moonlight could add
  double altitude_rad = 0.0;   ///< geometric, at the site
  bool any() const;
};

/// The Moon of `frame`'s sky clock as a light of the resident atmospheres
/// (frame.passes with their tables), decided per atmosphere: not lit without a
/// sky clock, for an atmosphere not resident, or where the test above finds
/// nothing it could show. The test depends on the camera, the exposure, the
/// colour weights and the tables, not on the projection: every node of a
/// cluster decides the same for each atmosphere, so no seam can come of it.
/// `moon_shadow`: the Earth's shadow on the Moon this frame (a lunar eclipse:
/// the Moon's light is the face's mean left; render/night/moon_in_shadow.h), or null.
MoonLight moon_light(const FrameInProgress& frame, const MoonInShadow* moon_shadow);

}  // namespace zenith::render
