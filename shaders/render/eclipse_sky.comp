#version 450
// Fills the eclipse-sky table of one atmosphere for one group of 4
// wavelengths (render/frame/eclipse_sky_table.h): per direction from the
// camera, the share of the sky-view table's light the Moon's shadow leaves.
// The sum is astro/eclipsed_sky.cpp's, operation for operation: along the
// view ray from the camera x to its end e, cut at t_k = d (k/N)², each table
// term splits by the tables' identity S(x → e) = Σ_k [T(x, p_k) S(p_k) −
// T(x, p_k+1) S(p_k+1)], and each segment is weighted by the shadow at its
// middle m_k (moon_shadow.glsl):
//   A share = Σ_k [V(m_k) ΔR_k P_R(ν) + V̄(m_k, v) Δmultiple_k] / Σ_k [ΔR_k P_R(ν) + Δmultiple_k]
//   (summed from the far end, so that V̄(m_k, v) knows the light arriving from
//   straight behind m_k — the segments beyond it and the far half of its own —
//   which the aerosols' forward share scatters on)
//   M share = Σ_k V(m_k) ΔM_k / Σ_k ΔM_k           (the Mie phase is the same along the ray)
// so that the tile pass draws (A · A share + M P_M(ν) · M share) E_sun: the
// sky-view table's fine detail (the horizon, the sun's azimuth) times a
// share that varies over tens of degrees. Without a Moon the shares are 1 to
// the float's rounding. On the ground half a third layer holds the share of
// the skylight left on the ground where the ray ends (MoonShadow::skylight_left);
// the direct sun's V, which changes sharply at the umbra's edge, is per pixel
// in atmosphere_tile.comp.
//
// A camera outside the shell (orbit) sums from where each ray enters the air,
// as astro/eclipsed_sky.cpp does (nothing scatters before it): the entry
// point's r = RT, μ and μs, the segment positions offset by the entry distance.
//
// Defines: those of atmosphere_common.glsl, MULTIPLE_SCATTERING, those of
// moon_shadow.glsl and eclipse_sky_mapping.glsl, ECLIPSE_SKY_SEGMENTS.
#include "atmosphere_common.glsl"
#include "frame.glsl"
#include "atmosphere_segment.glsl"
#include "moon_shadow.glsl"
#include "eclipse_sky_mapping.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = OUTPUT_IMAGE, rgba32f) uniform writeonly image2DArray eclipse_sky_table;

uniform float camera_r;             // [m], ≥ RB
uniform float camera_ground_power;  // r² − RB² [m²], in double on the CPU
uniform float theta_top;            // θ0: 0 inside the shell, π − asin(RT / r) outside (eclipse_sky_mapping.glsl)
uniform float theta_horizon;        // θh = π − asin(RB / r), in double on the CPU
uniform vec3 camera_up;             // world frame, unit
uniform vec3 azimuth_h, azimuth_w;  // φ = 0 toward h (the sun's azimuth), φ = π/2 toward w = up × h
uniform vec3 fill_sun;              // toward the sun, world frame
uniform int layer_base;             // ECLIPSE_SKY_LAYERS · wavelength group

/// The three table terms at distance t along the ray (r, μ, μs, ν), carried
/// to its start by T(x, p): zero at the ray's end, where nothing lies beyond.
struct Carried {
  vec4 rayleigh, mie, multiple;
};

Carried carried(real r, real mu, real mu_s, real nu, bool ground, real t, bool at_end) {
  Carried c;
  c.rayleigh = c.mie = c.multiple = vec4(0.0);
  if (at_end) return c;
  const real r_t = clamp(sqrt(t * t + real(2) * r * mu * t + r * r), RB, RT);
  const real mu_t = clamp_cosine((r * mu + t) / r_t);
  const real mu_s_t = clamp_cosine((r * mu_s + t * nu) / r_t);
  const ScatteringUV single = scattering_uvwz(r_t, mu_t, mu_s_t, nu, ground, ANGLE_MAPPING_DISTANCE);
  c.rayleigh = vec4(sample_table_4d(single_rayleigh_texture, single));
#if HAS_MIE
  c.mie = vec4(sample_table_4d(single_mie_texture, single));
#endif
#if MULTIPLE_SCATTERING
  c.multiple =
      vec4(sample_table_4d(multiple_texture, scattering_uvwz(r_t, mu_t, mu_s_t, nu, ground, ANGLE_MAPPING_BLENDED)));
#endif
  if (t > real(0)) {
    const vec4 T = vec4(transmittance(r, mu, t, ground));
    c.rayleigh *= T;
    c.mie *= T;
    c.multiple *= T;
  }
  return c;
}

void main() {
  const ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(ECLIPSE_SKY_AZIMUTH_TEXELS, ECLIPSE_SKY_ZENITH_TEXELS)))) return;
  // camera_top_power (atmosphere_segment.glsl): r² − RT², set for this fill; > 0 outside the shell.
  const bool outside = camera_top_power > 0.0;
  for (int half_index = 0; half_index < 2; ++half_index) {
    const bool ground = half_index == 1;
    float theta, phi;
    eclipse_sky_direction(texel, theta_top, theta_horizon, ground, theta, phi);
    const vec3 v = cos(theta) * camera_up + sin(theta) * (cos(phi) * azimuth_h + sin(phi) * azimuth_w);
    const real nu = clamp(real(dot(v, fill_sun)), real(-1), real(1));
    // Where the sum starts: the camera, or where the ray enters the shell
    // (the entry distance in the stable form C / (q + √(q² − C)), q = −r μ,
    // C = r² − RT²; a ray that grazes past the shell enters where it is closest).
    real r = real(camera_r), mu = clamp_cosine(real(cos(theta))), mu_s = clamp_cosine(real(dot(camera_up, fill_sun)));
    real entry = real(0);
    if (outside) {
      const real C = real(camera_top_power), q = -r * mu;
      entry = C / (q + sqrt(max(q * q - C, real(0))));
      mu = clamp_cosine((r * mu + entry) / RT);
      mu_s = clamp_cosine((r * mu_s + entry * nu) / RT);
      r = RT;
    }
    real d;
    if (ground) {
      // Distance to the ground in the same stable form, C = r² − RB² at the start.
      const real C = outside ? (RT - RB) * (RT + RB) : real(camera_ground_power), q = -r * mu;
      d = C / (q + sqrt(max(q * q - C, real(0))));
    } else {
      d = distance_to_top(r, mu);
    }
    const float phase_r = float(rayleigh_phase(nu));
    const vec4 phase_m = vec4(model_mie_phase(nu));
    vec4 day_a = vec4(0.0), dark_a = vec4(0.0), day_m = vec4(0.0), dark_m = vec4(0.0);
    // From the far end back to the camera: each segment's air then knows the light arriving from straight
    // behind its middle (the sums so far and the far half of its own, all carried to the camera alike),
    // which the aerosols' forward share scatters on.
    const float n = float(ECLIPSE_SKY_SEGMENTS);
    Carried far = carried(r, mu, mu_s, nu, ground, d, true);
    for (int k = ECLIPSE_SKY_SEGMENTS - 1; k >= 0; --k) {
      const real t_near = d * real(float(k * k) / (n * n)), t_far = d * real(float((k + 1) * (k + 1)) / (n * n));
      const Carried near = carried(r, mu, mu_s, nu, ground, t_near, false);
      const real t_mid = real(0.5) * (t_near + t_far);
      const float r_mid = float(sqrt(t_mid * t_mid + real(2) * r * mu * t_mid + r * r));
      const ShadowPlace middle = shadow_place(v * float(entry + t_mid), r_mid - float(RB));
      const vec4 V = shadow_direct_light(middle);
      const vec4 rayleigh = max(near.rayleigh - far.rayleigh, 0.0) * phase_r;
      const vec4 mie = max(near.mie - far.mie, 0.0);
      const vec4 multiple = max(near.multiple - far.multiple, 0.0);
#if MULTIPLE_SCATTERING
      // The far half of the segment's own light lies behind its middle too, its multiply scattered light
      // at the share of the light beyond (astro/eclipsed_sky.cpp).
      const vec4 day_beyond = day_a + day_m * phase_m, dark_beyond = dark_a + dark_m * phase_m;
      const bvec4 lit = greaterThan(day_beyond, vec4(0.0));
      const vec4 beyond = mix(vec4(0.0), dark_beyond / day_beyond, lit);
      const vec4 single_in = rayleigh + mie * phase_m;
      const vec4 behind_left = mix(vec4(-1.0),
                                   (dark_beyond + 0.5 * (V * single_in + beyond * multiple)) /
                                       (day_beyond + 0.5 * (single_in + multiple)),
                                   lit);
      dark_a += shadow_scattered_light(middle, v, behind_left) * multiple;
#endif
      day_a += rayleigh + multiple;
      dark_a += V * rayleigh;
      day_m += mie;
      dark_m += V * mie;
      far = near;
    }
    const int layer = layer_base + (ground ? ECLIPSE_SKY_GROUND : ECLIPSE_SKY_SKY);
    imageStore(eclipse_sky_table, ivec3(texel, layer), mix(vec4(1.0), dark_a / day_a, greaterThan(day_a, vec4(0.0))));
    imageStore(eclipse_sky_table, ivec3(texel, layer + 1),
               mix(vec4(1.0), dark_m / day_m, greaterThan(day_m, vec4(0.0))));
    if (ground) {
      // The skylight's share left where the ray meets the ground (MoonShadow::skylight_left).
      const vec3 at_ground = v * float(entry + d);
      const vec3 normal = normalize(camera_up * camera_r + at_ground);
      imageStore(eclipse_sky_table, ivec3(texel, layer + 2), shadow_skylight_left(shadow_place(at_ground, 0.0), normal));
    }
  }
}
