#version 450 core
// Single scattering S1_R, S1_M(r, μ, μs, ν) without phase functions for one group
// of 4 wavelengths: β ∫₀^d T(x, y) T(y, sun) ρ(y) dy with SCATTERING_SAMPLES
// intervals, each integrated by integrate_interval, T(x, y) from the view ray's
// samples (view_ray.glsl; cpu_precompute.cpp, compute_single_scattering). One
// dispatch covers the r layers from z_offset.
layout(local_size_x = 8, local_size_y = 8) in;

#include "atmosphere_common.glsl"
#include "view_ray.glsl"

layout(binding = OUTPUT_IMAGE, rgba32f) uniform writeonly image3D single_rayleigh_image;
#if HAS_MIE
layout(binding = SECOND_OUTPUT_IMAGE, rgba32f) uniform writeonly image3D single_mie_image;
#endif

void main() {
  const ivec3 p = ivec3(gl_GlobalInvocationID.xy, z_offset + int(gl_GlobalInvocationID.z));
  if (p.x >= SCATTERING_NU * SCATTERING_MU_S || p.y >= SCATTERING_MU || p.z >= SCATTERING_R) return;
  const ScatteringCoordinates c = scattering_texel_coordinates(p.x, p.y, p.z, ANGLE_MAPPING_DISTANCE);
  const real d = distance_to_nearest_boundary(c.r, c.mu, c.hits_ground);
  const real lowest = lowest_point_distance(c.r, c.mu, d, c.hits_ground);
  real previous_t = real(0);
  real4 rayleigh = real4(0), prev_r = real4(0);
#if HAS_MIE
  real4 mie = real4(0), prev_m = real4(0);
#endif
  for (int i = 0; i <= SCATTERING_SAMPLES; ++i) {
    const real t = ray_sample_distance(i, SCATTERING_SAMPLES, d, lowest);
    PRECISE real dx = t - previous_t;
    previous_t = t;
    PRECISE real r_t = clamp(sqrt(t * t + real(2) * c.r * c.mu * t + c.r * c.r), RB, RT);
    PRECISE real mu_s_t = clamp((c.r * c.mu_s + t * c.nu) / r_t, real(-1), real(1));
    const real h = r_t - RB;
    const real4 tt = view_transmittance[view_ray_sample_index(p.z, p.y, i)] * transmittance_to_sun(r_t, mu_s_t);
    const real4 f_r = tt * rayleigh_density(h);
    if (i > 0) rayleigh += integrate_interval(prev_r, f_r, dx);
    prev_r = f_r;
#if HAS_MIE
    const real4 f_m = tt * mie_density(h);
    if (i > 0) mie += integrate_interval(prev_m, f_m, dx);
    prev_m = f_m;
#endif
  }
  imageStore(single_rayleigh_image, p, vec4(rayleigh * wavelength_field(FIELD_RAYLEIGH_SCATTERING)));
#if HAS_MIE
  imageStore(single_mie_image, p, vec4(mie * wavelength_field(FIELD_MIE_SCATTERING)));
#endif
}
