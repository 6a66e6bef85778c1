#version 450
// The tiles exactly one atmosphere's shell can touch (render/renderer.cpp),
// for one group of 4 wavelengths, in one pass straight to the band's output:
// every pixel's ray, the body it meets and its albedo, this atmosphere's
// segment S, T of the ray, what lies behind it (an airless body lit by the
// sun, the sun's disc) seen through T, the group's colour (group_light.glsl).
// No G-buffer, no running radiance and transmittance images, no resolve pass:
// the G-buffer path (gbuffer.comp, atmosphere_pass.comp, resolve.comp) is
// kept for tiles where shells overlap, which need front-to-back composition.
//
// Two ways to S (SKY_VIEW):
//   0  the 4D tables along the ray (atmosphere_segment.glsl): any camera,
//      from the ground to space and the limb, any body inside the shell;
//   1  a camera inside the shell, in tiles where no other body inside the
//      shell can be: S, and the ground's light, by direction from the frame's
//      sky-view table (sky_view.comp) with hardware bilinear filtering:
//        sky:    S = A + M P_M(ν)                          T = T(r, μ → top)
//        ground: S = A + M P_M(ν) + ρ (G_sun V + G_sky)    T = 0
//      T only where something can lie behind the sky (a moon, the sun's
//      disc), from the transmittance table as in variant 0.
//
// Each tile list is dispatched with the program compiled for what its tiles
// can hold (render/renderer.cpp decides per tile from the tiles' cones): Mesa's
// llvmpipe, 8 pixels per SIMD vector, runs the code of every branch for every
// pixel even where no pixel takes it, so what a tile cannot hold must not be
// in its program. (A cold start draws every kind with TILE_GROUND 2, the same
// pixels, until the kinds' own are built: RenderOptions::tile_programs.)
//   TILE_GROUND  0: no ray meets this planet; 1: every ray does; 2: some
//   TILE_OTHERS  0: no other body; 1: other bodies, all beyond the shell
//                (seen through it); 2: one may be inside the shell (aerial
//                perspective, SKY_VIEW 0 only)
//   SUN          1: the sun's disc can be in the tile
// and, in the frames of a solar eclipse (render/frame/eclipse_sky_table.h),
//   ECLIPSE_SKY  1: the Moon's shadow on the air: A and M times their shares
//                left from the frame's eclipse-sky table (eclipse_sky.comp),
//                the ground's skylight times the share left from the same
//                table and its direct sun times V per pixel (moon_shadow.glsl);
//                with its defines (EclipseSkyTable::defines()). SKY_VIEW 1
//                multiplies the sky-view table's terms; SKY_VIEW 0 (a camera
//                in orbit, bodies inside the shell) the 4D tables' terms
//                (atmosphere_segment.glsl's hook, the functions below)
// Other defines: those of atmosphere_common.glsl, MULTIPLE_SCATTERING,
// ECLIPSES, SUN_DISC, LIMB_DARKENING.
#include "atmosphere_common.glsl"
#include "frame.glsl"
#include "atmosphere_segment.glsl"
#include "group_light.glsl"
#include "surface_albedo.glsl"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

#if ECLIPSE_SKY
#include "moon_shadow.glsl"
#include "eclipse_sky_mapping.glsl"
/// The frame's eclipse-sky table (eclipse_sky.comp): ECLIPSE_SKY_LAYERS layers per group.
layout(binding = ECLIPSE_SKY_UNIT) uniform sampler2DArray eclipse_sky_table;
uniform int eclipse_sky_layer_base;            // ECLIPSE_SKY_LAYERS · wavelength group
uniform vec3 eclipse_sky_h, eclipse_sky_w;     // its azimuth's axes: φ = 0 toward h, π/2 toward w
uniform float eclipse_sky_theta_top;           // θ0 of its mapping: 0 inside the shell
uniform float eclipse_sky_theta_horizon;       // θh of its mapping [rad]

/// The table's shares along `ray` from the camera (to the ground where
/// `ground`): atmosphere_segment.glsl's hook for SKY_VIEW 0, and SKY_VIEW 1's.
/// The skylight's share only where `ground`.
EclipseShares eclipse_shares(vec3 ray, bool ground) {
  const vec3 up = -the_body.centre.xyz;
  const float theta = acos(clamp(dot(up, ray), -1.0, 1.0));
  const vec2 uv = eclipse_sky_uv(theta, atan(dot(ray, eclipse_sky_w), dot(ray, eclipse_sky_h)),
                                 eclipse_sky_theta_top, eclipse_sky_theta_horizon, ground);
  const float layer = float(eclipse_sky_layer_base + (ground ? ECLIPSE_SKY_GROUND : ECLIPSE_SKY_SKY));
  EclipseShares shares;
  shares.smooth_part = texture(eclipse_sky_table, vec3(uv, layer));
  shares.mie = texture(eclipse_sky_table, vec3(uv, layer + 1.0));
  shares.skylight = ground ? texture(eclipse_sky_table, vec3(uv, layer + 2.0)) : vec4(1.0);
  return shares;
}
/// 1: the ground's direct sun takes V from the shadow's tables; 0: the Moon
/// is a body of the scene, whose shadow on the ground sunlight_left already
/// draws exactly (frame.glsl's covered_moments), and the tables shade the air only.
uniform int eclipse_shadows_ground;
vec4 eclipse_direct_light(vec3 point) {
  return eclipse_shadows_ground != 0 ? shadow_direct_light(shadow_place(point, 0.0)) : vec4(1.0);
}
#endif

// Something can lie behind the atmosphere in these tiles: light seen through T.
#define BEHIND ((SUN && TILE_GROUND != 1) || TILE_OTHERS != 0)

#if SKY_VIEW
#include "sky_view_mapping.glsl"
/// The frame's sky-view table (sky_view.comp): SKY_VIEW_LAYERS layers per group.
layout(binding = SKY_VIEW_UNIT) uniform sampler2DArray sky_view_table;
uniform int sky_view_layer_base;       // SKY_VIEW_LAYERS · wavelength group
uniform float sky_view_theta_horizon;  // zenith angle of the geometric horizon at the camera [rad]

/// Variant 1's radiance: the camera is inside the shell and nothing but this
/// planet's ground lies inside it along the ray; `behind` is the light of
/// what lies beyond the shell.
vec4 sky_view_radiance(vec3 ray, bool own_ground, float hit_distance, vec3 albedo, vec4 behind) {
  const vec3 up = -the_body.centre.xyz;
  const float mu_view = dot(up, ray), mu_sun = dot(up, sun_direction);
  const vec3 ray_horizontal = ray - mu_view * up, sun_horizontal = sun_direction - mu_sun * up;
  const float norms = dot(ray_horizontal, ray_horizontal) * dot(sun_horizontal, sun_horizontal);
  // At the zenith or with the sun overhead every azimuth is the same direction.
  const float cos_phi = norms > 1e-12 ? dot(ray_horizontal, sun_horizontal) * inversesqrt(norms) : 1.0;
  const float theta = acos(clamp(mu_view, -1.0, 1.0));
  const vec2 uv = sky_view_uv(theta, cos_phi, sky_view_theta_horizon, own_ground);
  const float layer = float(sky_view_layer_base + (own_ground ? SKY_VIEW_GROUND : SKY_VIEW_SKY));
  vec4 S = texture(sky_view_table, vec3(uv, layer));
#if HAS_MIE
  vec4 S_mie = texture(sky_view_table, vec3(uv, layer + 1.0)) * vec4(model_mie_phase(real(dot(ray, sun_direction))));
#endif
#if ECLIPSE_SKY
  // The shares the Moon's shadow leaves of A and M along this direction.
  const EclipseShares shares = eclipse_shares(ray, own_ground);
  S *= shares.smooth_part;
#if HAS_MIE
  S_mie *= shares.mie;
#endif
#endif
#if HAS_MIE
  S += S_mie;
#endif
  vec4 L = S * sun_irradiance;
#if TILE_GROUND != 0
  // G_sun and G_sky exist only in the ground half: for a sky pixel of a mixed
  // tile these read the ground half's A and M, and are not used.
  const vec4 g_sun = texture(sky_view_table, vec3(uv, layer + 2.0));
  const vec4 g_sky = texture(sky_view_table, vec3(uv, layer + 3.0));
#if ECLIPSE_SKY
  // The Moon's shadow on the ground: V of the direct sun, the skylight's share left.
  const vec4 ground = reflectance(albedo) * (g_sun * sunlight_left(ray * hit_distance, planet) *
                                                 eclipse_direct_light(ray * hit_distance) +
                                             g_sky * shares.skylight);
#else
  const vec4 ground = reflectance(albedo) * (g_sun * sunlight_left(ray * hit_distance, planet) + g_sky);
#endif
  if (own_ground) L += ground * sun_irradiance;
#endif
#if BEHIND && TILE_GROUND != 1
  if (!own_ground) L += vec4(transmittance_to_top(real(the_body.centre.w), real(mu_view))) * behind;
#endif
  return L;
}
#endif

void main() {
  ivec2 p;
  if (!tile_pixel(p)) return;
  vec4 L = vec4(0.0);
  vec3 ray;
  if (pixel_ray(p, ray)) {
    // The body the ray meets (−1: none) and where.
    float t = -1.0;
    int b = -1;
#if TILE_OTHERS != 0
    b = nearest_body(ray, t);
#elif TILE_GROUND == 1
    // Every ray of these tiles meets the planet (the tile's cone lies within
    // its disc, with a pixel's margin).
    t = max(intersect_body(the_body, ray), 0.0);
    b = planet;
#elif TILE_GROUND == 2
    t = intersect_body(the_body, ray);
    b = t >= 0.0 ? planet : -1;
#endif
    vec3 albedo = vec3(0.0);
#if TILE_OTHERS != 0
    albedo = surface_albedo(max(b, 0), ray, t, body_normal(max(b, 0), ray, t));
#elif TILE_GROUND != 0
    albedo = surface_albedo(the_body, ray, t, body_normal(the_body, ray, t));
#endif
    // What lies behind this atmosphere: another body (airless, or it would
    // have a shell here too) or the sun's disc; this planet's ground is its own.
    vec4 behind = vec4(0.0);
#if SUN && TILE_GROUND != 1
    if (b < 0) behind = sun_disc(ray);
#endif
#if TILE_OTHERS != 0
    if (b >= 0 && b != planet) behind = airless_surface(b, ray, t, albedo);
#endif
#if SKY_VIEW
    L = sky_view_radiance(ray, b == planet, t, albedo, behind);
#else
    real4 radiance, transmittance_segment;
    if (atmosphere_segment(ray, t, b, real4(reflectance(albedo)), radiance, transmittance_segment))
      L = vec4(radiance) * sun_irradiance + vec4(transmittance_segment) * behind;
    else
      L = behind;
#endif
  }
  add_group_rgb(p, L);
}
