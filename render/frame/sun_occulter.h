#pragma once
// The Moon in front of the sun's disc: a solar eclipse as the sun's passes
// draw it (docs/rendering.md, "Sun, shadows, eclipses"). From the scene's sky
// clock, the Moon's topocentric place (ERFA's Moon98, geometric, as the Sun's)
// in the camera's local horizon; where its disc overlaps the sun's, the pixels
// of the sun's disc behind it are masked (shaders/render/sun_disc.glsl,
// antialiased over the sun's pixel footprint), and a sun drawn as a Gaussian
// (smaller than the pixels) keeps the share of the limb-darkened disc's light
// the Moon leaves, per wavelength (astro::limb_darkened_obscuration). The
// corona is drawn around a disc the Moon overlaps (Baumbach's profile,
// sun_disc.glsl), out to kCoronaOuterRadii.
//
// Before the discs touch and after they part, the Moon's penumbra can already
// lie on the air the camera sees (a few hundred kilometres around it): while
// it is near enough to matter, `shadow` holds the eclipse's geometry for the
// sky's passes (render/frame/eclipse_sky_table.h).
//
// The test is one ephemeris evaluation and one angle: no Moon (no sky clock,
// RenderOptions::moon off) or a Moon whose shadow is far from the air in view,
// and nothing changes, bit for bit.
//
// In a scene of bodies (no sky clock) the Moon is a body like the others: it
// is drawn, and covers the sun's disc, as a body. What it adds here is its
// shadow on another body's air (an airless body's umbra on the Earth seen
// from space), found from the bodies' places in the same way.
#include <cstddef>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "astro/moon_shadow.h"
#include "render/frame/frame_sky.h"
#include "scene/scene.h"

namespace zenith::render {

/// How far from the sun's centre the corona is drawn in an eclipse, in solar
/// radii (shaders/render/sun_disc.glsl's kCoronaOuterRadii): beyond it, Baumbach's
/// profile is under 1e-9 of the disc.
inline constexpr double kCoronaOuterRadii = 6.0;

struct SunOcculter {
  glm::dvec3 direction{0.0, 0.0, 1.0};  ///< world, unit: the Moon's centre (geometric, as the sun's direction)
  double angular_radius_rad = 0.0;      ///< 0: nothing in front of the sun this frame
  double separation_rad = 0.0;          ///< between the discs' centres
  /// Per wavelength: the share of the disc's light the Moon leaves (the
  /// limb-darkened disc's, or the uniform disc's without limb darkening).
  std::vector<double> uncovered;
  /// The Moon's shadow may lie on the air the camera sees (the clock's planet
  /// has an atmosphere, and the camera's distance from the shadow's axis is
  /// under two penumbra radii plus the air's reach): its geometry centred on
  /// that planet, world-oriented (astro/moon_shadow.h).
  std::optional<astro::EclipseGeometry> shadow;
  /// With `shadow`: the index in Scene::bodies of the planet whose air it lies on.
  std::size_t shadow_planet = 0;
  /// With `shadow`: the Moon is a body of the scene, whose own shadow on the
  /// planet's ground the bodies' code draws exactly (frame.glsl's
  /// covered_moments), so the eclipse tables darken only the air and its skylight.
  bool shadow_caster_is_a_body = false;
  /// Whether `shadow` lies on the air of body `body` (an index in Scene::bodies).
  bool shadow_on_the_air_of(int body) const { return shadow && body == static_cast<int>(shadow_planet); }
  /// With `shadow`: how far the nearest air in view lies from the shadow's
  /// axis, in penumbra radii (≤ 1: the penumbra reaches it; ≥ 2: V = V̄ = 1 there).
  double air_from_axis_penumbrae = 0.0;
  bool any() const { return angular_radius_rad > 0.0; }
};

/// The Moon of `scene`'s sky clock in front of its sun, or none (see above);
/// `sky`: that clock's ephemeris for the frame. Without a sky clock, the
/// shadow of an airless body on the air of the body with an atmosphere
/// nearest the camera, where one reaches the air in view (the nearest to it
/// of those that do); never a disc in front of the sun.
SunOcculter sun_occulter(const scene::Scene& scene, const FrameSky& sky, bool limb_darkening);

}  // namespace zenith::render
