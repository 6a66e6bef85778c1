#version 450 core
// Radiance of order n, L_n(r, μ, μs, ν) = ∫₀^d T(x, y) J_n(y) dy along the ray with
// the rule of single scattering (T(x, y) from the view ray's samples, view_ray.glsl;
// from coarse_ray_first_order on every sample_stride-th of them and the last,
// next_ray_sample), J read geometrically in μs as on the CPU (the deep twilight's
// e-fold fall per degree), for one group of 4 wavelengths; written as the delta of this
// order and added to the multiple-scattering table
// (cpu_precompute.cpp, compute_multiple_scattering).
layout(local_size_x = 8, local_size_y = 8) in;

#include "atmosphere_common.glsl"
#include "view_ray.glsl"

layout(binding = DENSITY_UNIT) uniform sampler3D density_texture;
layout(binding = OUTPUT_IMAGE, rgba32f) uniform writeonly image3D delta_radiance_image;
layout(binding = SECOND_OUTPUT_IMAGE, rgba32f) uniform image3D multiple_image;
uniform int sample_stride;  // PrecomputeOptions::ray_sample_stride(order)

void main() {
  const ivec3 p = ivec3(gl_GlobalInvocationID.xy, z_offset + int(gl_GlobalInvocationID.z));
  if (p.x >= SCATTERING_NU * SCATTERING_MU_S || p.y >= SCATTERING_MU || p.z >= SCATTERING_R) return;
  const ScatteringCoordinates c = scattering_texel_coordinates(p.x, p.y, p.z, ANGLE_MAPPING_BLENDED);
  const real d = distance_to_nearest_boundary(c.r, c.mu, c.hits_ground);
  const real lowest = lowest_point_distance(c.r, c.mu, d, c.hits_ground);
  real previous_t = real(0);
  real4 sum = real4(0), prev = real4(0);
  // ν is constant along the ray, the azimuth (u_ν) is not; r and μ at the
  // samples come from the ray's row (view_ray.glsl).
  ScatteringUV uv;
  const real theta_max = sun_theta_max();
  const int stride = coarse_ray_stride_for(c.mu, c.hits_ground, sample_stride);
  for (int i = 0; i <= SCATTERING_SAMPLES; i = next_ray_sample(i, stride, SCATTERING_SAMPLES)) {
    const real t = ray_sample_distance(i, SCATTERING_SAMPLES, d, lowest);
    PRECISE real dx = t - previous_t;
    previous_t = t;
    PRECISE real r_t = clamp(sqrt(t * t + real(2) * c.r * c.mu * t + c.r * c.r), RB, RT);
    PRECISE real mu_s_t = clamp((c.r * c.mu_s + t * c.nu) / r_t, real(-1), real(1));
    PRECISE real mu_t = clamp((c.r * c.mu + t) / r_t, real(-1), real(1));
    const int sample_index = view_ray_sample_index(p.z, p.y, i);
    uv.u_r = view_ray_uv[sample_index].x;
    uv.u_mu = view_ray_uv[sample_index].y;
    uv.u_mu_s = texture_coord_from_unit(unit_from_mu_s(mu_s_t, ANGLE_MAPPING_BLENDED, theta_max), SCATTERING_MU_S);
    uv.u_nu = scattering_u_nu(mu_t, mu_s_t, c.nu);
    const real4 j = sample_scattering_table_geometric_mu_s(density_texture, uv);
    const real4 f = view_transmittance[sample_index] * j;
    if (i > 0) sum += integrate_interval(prev, f, dx);
    prev = f;
  }
  imageStore(delta_radiance_image, p, vec4(sum));
  imageStore(multiple_image, p, imageLoad(multiple_image, p) + vec4(sum));
}
