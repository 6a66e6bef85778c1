#version 450
// Fills the sky-view table of one atmosphere for one group of 4 wavelengths,
// once per frame, from the 4D tables at the camera's radius r and sun cosine
// μs (render/frame/sky_view_table.h; texel ↔ direction in sky_view_mapping.glsl).
// Per texel (θ, φ) → μ = cos θ, ν = μ μs + √(1−μ²)√(1−μs²) cos φ, per unit
// solar irradiance:
//
//   sky half (rays that leave the atmosphere) and ground half (rays that end
//   on the planet's ground), layers A and M:
//     A = R(r, μ, μs, ν) P_R(ν) + multiple(r, μ, μs, ν)   Rayleigh and orders ≥ 2
//     M = M(r, μ, μs, ν)                                 single Mie, no phase
//   ground half only, where the ray meets the ground at distance d, the sun's
//   cosine there μs' = (r μs + d ν) / RB and T = T(r, μ, d) the transmittance
//   to it, the ground's light per unit albedo without the eclipses' V:
//     G_sun = T E_direct(μs') / π                         the direct sun
//     G_sky = T E_sky(μs') / π                            the sky's irradiance
//
// so that a pixel is A + M P_M(ν) (+ ρ (G_sun V + G_sky) on the ground), the
// Mie phase, whose forward peak no table of this size could hold, at the
// pixel's exact ν (atmosphere_tile.comp); what the table interpolates is
// smooth in direction. The transmittance along sky rays is not in the table:
// T(r, μ → top), needed only where something lies behind the sky, falls by
// orders of magnitude within a degree of the horizon and is read from the
// transmittance table per pixel.
//
// Defines: those of atmosphere_common.glsl, MULTIPLE_SCATTERING, ECLIPSES.
#include "atmosphere_common.glsl"
#include "frame.glsl"
#include "atmosphere_segment.glsl"
#include "sky_view_mapping.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = OUTPUT_IMAGE, rgba32f) uniform writeonly image2DArray sky_view_table;

uniform float camera_r;             // [m], in [RB, RT)
uniform float camera_ground_power;  // r² − RB² [m²], in double on the CPU
uniform float camera_mu_s;          // cosine of the sun's zenith angle at the camera
uniform float theta_horizon;        // θh = π − asin(RB / r), in double on the CPU
uniform int layer_base;             // SKY_VIEW_LAYERS · wavelength group

void main() {
  const ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(SKY_VIEW_AZIMUTH_TEXELS, SKY_VIEW_ZENITH_TEXELS)))) return;
  const real r = real(camera_r);
  const real mu_s = real(camera_mu_s);
  for (int half_index = 0; half_index < 2; ++half_index) {
    const bool ground = half_index == 1;
    float theta, cos_phi;
    sky_view_direction(texel, theta_horizon, ground, theta, cos_phi);
    const real mu = clamp_cosine(real(cos(theta)));
    const real nu = clamp(mu * mu_s + real(sin(theta)) * sqrt(max(real(1) - mu_s * mu_s, real(0))) * real(cos_phi),
                          real(-1), real(1));
    const Inscatter s = inscatter(r, mu, mu_s, nu, ground);
    const int layer = layer_base + (ground ? SKY_VIEW_GROUND : SKY_VIEW_SKY);
    imageStore(sky_view_table, ivec3(texel, layer), vec4(s.smooth_part));
    imageStore(sky_view_table, ivec3(texel, layer + 1), vec4(s.mie));
    if (ground) {
      // Distance to the ground in the stable form C / (q + √(q² − C)), q = −r μ > 0, C = r² − RB².
      const real C = real(camera_ground_power), q = -r * mu;
      const real d = C / (q + sqrt(max(q * q - C, real(0))));
      const real4 t = transmittance(r, mu, d, true);
      const real mu_s_ground = clamp_cosine((r * mu_s + d * nu) / RB);
      imageStore(sky_view_table, ivec3(texel, layer + 2), vec4(t * direct_irradiance(RB, mu_s_ground) / PI));
      imageStore(sky_view_table, ivec3(texel, layer + 3), vec4(t * sky_irradiance(mu_s_ground) / PI));
    }
  }
}
