#version 450
// One atmosphere's pass over the pixels its shell can touch (the tiles listed
// in Tiles), for one group of 4 wavelengths: paper section 5.2, Algorithm 1.
//
// Several atmospheres are composited front to back (render/renderer.cpp runs
// the passes in the order the camera meets the shells). Per pixel the passes
// keep a running radiance L and transmittance T (images radiance_sum and
// transmittance_product, initialised to 0 and 1); this pass adds T·S for the
// in-scattered radiance S of its segment of the ray and multiplies T by the
// segment's transmittance. Where the ray ends on this planet's own ground it
// adds the ground's reflected light too and sets T to 0: nothing behind is seen.
//
// Segment of the ray inside the shell, from the entry point x0 (the camera
// itself when it is inside) to the exit or to the hit point y of the G-buffer:
//   sky:               L += T · S(x0)                     T *= T(x0 → top)
//   other body inside: L += T · (S(x0) − T(x0,y) S(y))    T *= T(x0, y)   (aerial perspective)
//   own ground:        L += T · (S(x0) + T(x0,y) L_g)     T  = 0
// with L_g = ρ/π (E_sun T_sun(y) V + E_sky(y)) the Lambertian ground lit by the
// direct sun (partly below the horizon near sunset, eclipsed by other bodies:
// V) and the sky irradiance table. S(r, μ, μs, ν) = R(…) P_R(ν) + M(…) P_M(ν)
// + multiple(…), tables per unit solar irradiance, times E_sun at the end.
//
// Defines (render/renderer.cpp): those of atmosphere_common.glsl, plus
//   MULTIPLE_SCATTERING  0 drops the multiple-scattering table (single only)
//   ECLIPSES             0 drops the shadows of other bodies on the ground
#include "atmosphere_common.glsl"
#include "frame.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(binding = 0, rgba32f) uniform readonly image2D gbuffer_hit;
layout(binding = 1, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(binding = 2, rgba32f) uniform image2D radiance_sum;
layout(binding = 3, rgba32f) uniform image2D transmittance_product;

layout(binding = 1) uniform sampler3D single_rayleigh_texture;
layout(binding = 2) uniform sampler3D single_mie_texture;
layout(binding = 3) uniform sampler3D multiple_texture;
layout(binding = 4) uniform sampler2D irradiance_texture;

/// Tiles of 16×16 band pixels this atmosphere can touch: x | y << 16.
layout(std430, binding = 5) readonly buffer Tiles { uint tiles[]; };
uniform int tile_count;

uniform int planet;                 // index of the body this atmosphere surrounds
uniform float camera_top_power;     // |c|² − RT² [m²], in double on the CPU
uniform vec4 sun_irradiance;        // E_sun per wavelength of the group [W m^-2 nm^-1]
uniform vec4 albedo_from_r;         // reflectance of each wavelength from linear sRGB albedo
uniform vec4 albedo_from_g;
uniform vec4 albedo_from_b;

/// S(r, μ, μs, ν) per unit solar irradiance, phase functions applied.
real4 scattering(real r, real mu, real mu_s, real nu, bool hits_ground) {
  const ScatteringUV single = scattering_uvwz(r, mu, mu_s, nu, hits_ground, ANGLE_MAPPING_DISTANCE);
  real4 s = sample_scattering_table(single_rayleigh_texture, single) * rayleigh_phase(nu);
#if HAS_MIE
  s += sample_scattering_table(single_mie_texture, single) * mie_phase(nu);
#endif
#if MULTIPLE_SCATTERING
  s += sample_scattering_table(multiple_texture, scattering_uvwz(r, mu, mu_s, nu, hits_ground, ANGLE_MAPPING_BLENDED));
#endif
  return s;
}

/// Direct sun on a horizontal surface at radius r, per unit solar irradiance:
/// T_sun · μs · (fraction of the disc above the horizon). The fraction is the
/// area of the disc's part above the horizon line (a circular segment), so the
/// light fades over the ~0.5° of a sunset instead of switching off.
real4 direct_irradiance(real r, real mu_s) {
  const float mu_horizon = -sqrt(max(0.0, 1.0 - float(RB / r) * float(RB / r)));
  const float elevation = asin(clamp(float(mu_s), -1.0, 1.0)) - asin(mu_horizon);
  const float x = clamp(elevation / max(sun_angular_radius, 1e-6), -1.0, 1.0);
  const float fraction = (acos(-x) + x * sqrt(1.0 - x * x)) / 3.14159265;
  if (fraction <= 0.0 || mu_s <= real(0)) return real4(0);
  return transmittance_to_top(r, max(mu_s, real(mu_horizon))) * real(fraction) * mu_s;
}

void main() {
  const uint tile_index = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  if (tile_index >= uint(tile_count)) return;
  const uint tile = tiles[tile_index];
  const ivec2 p = ivec2(int(tile & 0xffffu), int(tile >> 16)) * 16 + ivec2(gl_LocalInvocationID.xy);
  if (any(greaterThanEqual(p, band_size))) return;
  const vec4 hit = imageLoad(gbuffer_hit, p);
  if (hit.z == 0.0) return;  // outside the projection's image
  vec4 T_so_far = imageLoad(transmittance_product, p);
  if (all(equal(T_so_far, vec4(0.0)))) return;  // an opaque surface in front
  vec3 ray;
  if (!pixel_ray(p, ray)) return;

  // The planet-centred frame: the camera at distance r along `up`.
  const vec3 up = -bodies[planet].centre.xyz;
  const float r_camera = bodies[planet].centre.w;
  const vec3 c = body_centre(planet);
  float q, disc;
  if (!sphere_chord(ray, bodies[planet].centre.xyz, r_camera, float(RT), camera_top_power, q, disc)) return;
  const float half_chord = sqrt(disc);
  // Entry (0 inside the shell) and exit distances along the ray.
  const bool inside = camera_top_power <= 0.0;
  const float d_exit = q + half_chord;
  if (d_exit <= 0.0) return;  // the shell is behind the camera
  const float d_entry = inside ? 0.0 : camera_top_power / (q + half_chord);
  const bool hits_body = hit.x >= 0.0;
  if (hits_body && hit.x <= d_entry) return;  // a body in front of the shell hides it
  const int hit_body = int(hit.y);
  const bool own_ground = hits_body && hit_body == planet;

  // The entry point x0: r, μ, μs there (the camera's own values when inside).
  real r, mu, mu_s;
  const real nu = real(dot(ray, sun_direction));
  if (inside) {
    r = real(r_camera);
    mu = real(dot(up, ray));
    mu_s = real(dot(up, sun_direction));
  } else {
    const vec3 x0 = ray * d_entry - c;
    r = RT;
    mu = real(-half_chord / float(RT));  // entering: the ray is half a chord before its closest approach
    mu_s = clamp(real(dot(x0, sun_direction) / float(RT)), real(-1), real(1));
  }
  r = clamp(r, RB, max(RT, r));
  mu = clamp_cosine(mu);

  // The ray (continued) ends on the ground: decided by the G-buffer for this
  // planet's own ground, so the table halves meet exactly where the ground's edge is drawn.
  const bool continues_to_ground = own_ground || (hits_body && ray_hits_ground(r, mu));
  real4 radiance = scattering(r, mu, mu_s, nu, continues_to_ground);
  real4 transmittance_segment;

  if (own_ground) {
    const real d = real(hit.x - d_entry);
    transmittance_segment = transmittance(r, mu, d, true);
    const vec3 n = body_normal(planet, ray, hit.x);
    const real mu_s_ground = real(dot(n, sun_direction));
    const vec3 albedo = imageLoad(gbuffer_albedo, p).rgb;
    const real4 rho = real4(albedo_from_r * albedo.r + albedo_from_g * albedo.g + albedo_from_b * albedo.b);
    const real visibility = real(sun_visibility(ray * hit.x, planet));
    const real2 uv = irradiance_uv(RB, mu_s_ground);
    const real4 sky = sample_table_2d(irradiance_texture, IRRADIANCE_MU_S, IRRADIANCE_R, uv.x, uv.y);
    const real4 ground = rho / PI * (direct_irradiance(RB, mu_s_ground) * visibility + sky);
    radiance += transmittance_segment * ground;
    transmittance_segment = real4(0);
  } else if (hits_body && hit.x < d_exit) {
    // Another body inside the shell: aerial perspective S(x0) − T(x0, y) S(y).
    const real d = real(hit.x - d_entry);
    transmittance_segment = transmittance(r, mu, d, continues_to_ground);
    const real r_y = clamp(sqrt(d * d + real(2) * r * mu * d + r * r), RB, RT);
    const real mu_y = clamp_cosine((r * mu + d) / r_y);
    const real mu_s_y = clamp_cosine((r * mu_s + d * nu) / r_y);
    radiance = max(radiance - transmittance_segment * scattering(r_y, mu_y, mu_s_y, nu, continues_to_ground), real4(0));
  } else {
    transmittance_segment = transmittance_to_top(r, mu);
  }

  const vec4 L = imageLoad(radiance_sum, p);
  imageStore(radiance_sum, p, L + T_so_far * vec4(radiance) * sun_irradiance);
  imageStore(transmittance_product, p, T_so_far * vec4(transmittance_segment));
}
