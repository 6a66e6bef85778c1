#version 450
// The night sky's own light joins the band's output (render/night/star_pass.h;
// docs/night-sky.md, "Rendering the night sky"), after the atmosphere passes
// and before the band leaves (a file's readback or the live display pass):
//
//   * the Moon's disc where it is larger than a pixel (a smaller Moon is a
//     point source among the stars): the Lommel–Seeliger law of
//     astro/moon_photometry.h, L = L(1, 1) · 2μ0/(μ0 + μ), its phase from the
//     sun's direction on each point of the sphere, its edge antialiased over
//     the pixel's footprint; with moon_mapped, each point's albedo from the
//     Moon's map (render/night/moon_albedo_map.h) at its selenographic place;
//     with moon_shadowed (a lunar eclipse), each point's colour from a table
//     by its distance from the Earth's shadow's axis (the sunlight refracted
//     and extinguished through the Earth's air: render/night/moon_in_shadow.h);
//   * with NIGHT_FLOOR, the natural night sky (airglow with van Rhijn's
//     brightening, zodiacal light, starlight) through the line of sight's
//     transmittance, plus the artificial glow of light pollution: a table of
//     linear sRGB × exposure against the view ray's cosine to the camera's up,
//     computed on the CPU from astro/night_sky_floor.h and
//     astro/light_pollution.h (render/night/night_sky_table.h), on every ray
//     that meets no body (the ground included).
//
// The tiles listed are the band's drawn tiles (add to what is there) or, with
// `overwrite`, tiles no pass drew (whose output holds stale values: replaced)
// where a star's splat or the Moon's disc reaches them. The stars themselves
// join after this pass, pixel by pixel (star_pixels.comp).
// Each list is dispatched with the program compiled for what its tiles hold
// (render/night/star_pass.cpp), since llvmpipe runs every branch a program has
// for every pixel (the Moon's disc code and the star accumulator's reads, never
// taken in most tiles, were half of the pass on a night ground view):
//   NIGHT_FLOOR   the night floor's table
//   NIGHT_MOON    the Moon's disc can be in the tiles
//   NIGHT_BODIES  0: no body can be in the tiles (BandTiles::bodies), so every
//                 ray with a pixel is sky; 1: the ray's nearest body decides

#include "frame.glsl"
#include "frame_rgb.glsl"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

uniform bool overwrite;

#if NIGHT_FLOOR || NIGHT_MOON
/// The night floor's table (NIGHT_FLOOR), then the eclipsed Moon's (moon_shadow_first …).
layout(std430, binding = NIGHT_SKY_TABLE_BINDING) readonly buffer NightSkyTable { vec4 night_sky_table[]; };
#endif

#if NIGHT_MOON
uniform vec3 moon_direction;  // world, unit: the disc's centre (refracted)
uniform float moon_radius;    // angular radius [rad]
uniform vec3 moon_rgb;        // 2 L_LS(1, 1) through the line of sight, linear sRGB × exposure
// The Moon's face: relative albedo (mean 1 over the lit disc seen: moon_rgb is
// divided by it) at each point's selenographic longitude and latitude.
uniform bool moon_mapped;
uniform vec3 moon_axis_x, moon_axis_y, moon_axis_z;  // world: toward (0°, 0°), (90° E, 0°), the north pole
uniform float moon_map_lod;  // log2(a pixel's arc on the Moon / a texel's) at the disc's centre, ≥ 0
layout(binding = MOON_ALBEDO_UNIT) uniform sampler2D moon_albedo;  // x: longitude −180°…180°, y: latitude 90°…−90°
// A lunar eclipse: the disc's rgb × exposure at moon_shadow_entries distances
// from the shadow's axis over [0, moon_shadow_reach] (moon_rgb beyond).
uniform bool moon_shadowed;
uniform vec3 moon_shadow_centre;  // the Moon's centre from the Earth's centre [m], world
uniform vec3 moon_shadow_axis;    // unit, away from the Sun
uniform float moon_shadow_radius;  // the Moon's radius [m]
uniform float moon_shadow_reach;   // [m]
uniform int moon_shadow_first, moon_shadow_entries;

/// The disc's rgb at the point of the Moon's sphere whose outward normal is `normal`.
vec3 moon_colour(vec3 normal) {
  if (!moon_shadowed) return moon_rgb;
  const vec3 p = moon_shadow_centre + moon_shadow_radius * normal;
  const float y = length(p - dot(p, moon_shadow_axis) * moon_shadow_axis);
  if (y >= moon_shadow_reach) return moon_rgb;
  const float f = y / moon_shadow_reach * float(moon_shadow_entries - 1);
  const int j = min(int(f), moon_shadow_entries - 2);
  return mix(night_sky_table[moon_shadow_first + j].rgb, night_sky_table[moon_shadow_first + j + 1].rgb, f - float(j));
}

/// The Moon's light along `ray`: on the sphere's point seen there (small
/// angles: its offset from the centre in units of the radius is sin θ of that
/// point from the sub-observer point), L ∝ μ0/(μ0 + μ), μ the cosine toward us,
/// μ0 toward the sun (0 on the night side); × the pixel's coverage of the disc.
vec3 moon_light(vec3 ray) {
  const float d = angle_between(ray, moon_direction);
  const float coverage = clamp((moon_radius - d) / max(pixel_footprint, 1e-7) + 0.5, 0.0, 1.0);
  if (coverage <= 0.0) return vec3(0.0);
  const vec3 offset = ray - moon_direction * dot(ray, moon_direction);
  const float s = min(d / moon_radius, 0.999);
  const vec3 across = length(offset) > 0.0 ? normalize(offset) : vec3(0.0);
  const float mu = sqrt(1.0 - s * s);
  const vec3 normal = -moon_direction * mu + across * s;
  const float mu0 = dot(normal, sun_direction);
  if (mu0 <= 0.0) return vec3(0.0);
  float albedo = 1.0;
  if (moon_mapped) {
    // The point's selenographic place; a pixel covers 1/μ more arc across the
    // limb than along it: the level of their geometric mean.
    const vec3 body = vec3(dot(normal, moon_axis_x), dot(normal, moon_axis_y), dot(normal, moon_axis_z));
    const vec2 uv = vec2(atan(body.y, body.x) / (2.0 * PI_F) + 0.5, 0.5 - asin(clamp(body.z, -1.0, 1.0)) / PI_F);
    albedo = textureLod(moon_albedo, uv, moon_map_lod - 0.5 * log2(max(mu, 1e-3))).r;
  }
  return moon_colour(normal) * (albedo * mu0 / (mu0 + mu)) * coverage;
}
#endif

#if NIGHT_FLOOR
/// Entry j at t = j / (n − 1) of μ = μh + (1 − μh) t² (μ the ray's cosine to
/// `night_up`, μh the ground's horizon): the sky's night light, rgb × exposure.
uniform int night_sky_entries;
uniform vec3 night_up;
uniform float night_horizon_mu;

vec3 night_sky_light(vec3 ray) {
  const float x = max(dot(ray, night_up) - night_horizon_mu, 0.0) / (1.0 - night_horizon_mu);
  const float f = sqrt(x) * float(night_sky_entries - 1);
  const int j = min(int(f), night_sky_entries - 2);
  return mix(night_sky_table[j].rgb, night_sky_table[j + 1].rgb, f - float(j));
}
#endif

void main() {
  ivec2 p;
  if (!tile_pixel(p)) return;
  // Only pixels that show the sky get the night's light: not a fisheye's
  // corners beyond its circle, a warp's pixels beyond its mesh, nor a pixel
  // whose ray ends on the ground or another body.
  vec3 ray;
  bool sky = pixel_ray(p, ray);
#if NIGHT_BODIES
  float distance_m;
  sky = sky && nearest_body(ray, distance_m) < 0;
#endif
  vec3 add = vec3(0.0);
  if (sky) {
#if NIGHT_FLOOR
    add += night_sky_light(ray);
#endif
#if NIGHT_MOON
    add += moon_light(ray);
#endif
  }
  const vec3 before = overwrite ? vec3(0.0) : load_frame_rgb(p);
  store_frame_rgb(p, clip_negative(before + add));
}
