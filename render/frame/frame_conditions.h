#pragma once
// What a frame's view can need, decided on the CPU before its passes are
// chosen (render/renderer.cpp): whether eclipses can happen, whether every
// albedo lookup is at the maps' full resolution, whether the sky-view table is
// accurate enough for the camera. A CPU rasterizer runs all the code a program
// has, so what a frame cannot need is compiled out (FrameVariant,
// render/frame/gpu_atmosphere.h). No GL.
#include "scene/scene.h"

namespace zenith::render {

/// Whether some body's shadow (its penumbra) can fall on another: then the
/// passes are compiled with the eclipse code (frame.glsl's covered_moments),
/// which a CPU rasterizer would otherwise run for every lit pixel in vain. For
/// an occluder of radius a at o and a receiver of radius b at c: the points
/// that see part of the sun (angular radius α, direction s) behind the
/// occluder lie within a + d tan α (·1.01, and a metre) of the shadow axis
/// through o, at d = (o − p)·s > 0 in front of them; the receiver's nearest
/// point is at least (its centre's distance from the axis) − b from it.
/// An occluder with an atmosphere casts its shadow out to the top of its air
/// (shadow_casting_radius_m; render/frame/air_shadows.h).
bool eclipses_possible(const scene::Scene& scene);

/// The outer radius of the shadow a body casts: the top of its air where it
/// has one (the sunlight refracted and dimmed through it), else its own radius.
double shadow_casting_radius_m(const scene::Body& body);

/// Whether the Moon can cover the sun in this frame's sky: the scene keeps a
/// sky clock (the Moon by date and place) and the Moon is drawn
/// (`moon_drawn`: RenderOptions::night_sky.moon); or, in a scene of bodies
/// where bodies shadow one another (`bodies_shadow`:
/// RenderOptions::atmosphere.eclipses), an airless body's shadow can fall on
/// another's air (airless_shadow_on_air_possible). Then the frame places the Moon as the
/// sun's occulter (render/frame/sun_occulter.h), and the renderer keeps the
/// sky-view table at every frame size, since the Moon's shadow on the air is
/// drawn from it.
bool moon_can_eclipse_the_sun(const scene::Scene& scene, bool moon_drawn, bool bodies_shadow);

/// Whether the shadow of a body without an atmosphere can reach the air of one
/// with an atmosphere (shadow_on_air_possible, for some pair).
bool airless_shadow_on_air_possible(const scene::Scene& scene);

/// Whether `occluder`, without an atmosphere, can shadow the air of
/// `receiver`, with one, as render/frame/sun_occulter.h draws it: the test of
/// eclipses_possible with the top of the receiver's atmosphere for its
/// radius; the occluder outside that air (as the shadow's model has it), and
/// covering at least a tenth of the sun's disc from the air nearest it. A
/// smaller body (a spacecraft) takes under a tenth of the light there, over
/// a patch far finer than the eclipse-sky table's texels: its shadow on the
/// ground, which the bodies' code draws, is all of it that shows.
bool shadow_on_air_possible(const scene::Scene& scene, const scene::Body& occluder, const scene::Body& receiver);

/// Whether every albedo lookup of the frame is at level 0 of the maps
/// (surface_albedo.glsl: lod = max(0, log2(footprint / texel))): a pixel's
/// footprint on a body is at most pixel angle × distance / 0.05 (the clamp of
/// the incidence cosine), and nothing of a sphere seen from outside lies
/// farther than its horizon, √(D² − R²). Then the passes sample level 0 with a
/// constant level (ALBEDO_LOD0): the same texels, without the per-pixel mip
/// selection a CPU rasterizer pays for.
bool albedo_at_full_resolution(const scene::Scene& scene, double pixel_angle, int map_width);

/// Where the sky-view table is as good as the 4D lookups per pixel, for a
/// camera at radius r inside the shell [RB, RT] with the sun's cosine μs
/// (measured with render_bench --sky-view-error on horizon views, 1280×720 with
/// 10° and 79° fields, paper tables; docs/rendering-performance.md): low in the
/// atmosphere (up to 2 % of its thickness: 2 km on Earth) always; up to 20 %
/// while the sun is above the camera's horizon. Higher, and in twilight above
/// the lowest layer, the light at the horizon changes within hundredths of a
/// degree (the limb, the Earth's shadow) and 64 zenith texels a half would
/// differ by up to 25 % there: the 4D lookups stay, as from space.
bool sky_view_accurate(double r, double ground_radius, double top_radius, double mu_s);

}  // namespace zenith::render
