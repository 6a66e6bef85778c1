#version 450 core
// T(x, y_i) and (u_r, u_μ) at the samples of each view ray of the scattering table
// (view_ray.glsl) for one group of 4 wavelengths; T by accumulating the optical
// depth along the ray, OPTICAL_DEPTH_SUBSTEPS log-linear steps per interval
// (cpu_precompute.cpp: view_ray_samples, the same operations in the same order).
// VIEW_MAPPING: the μ mapping of the stage that reads the samples
// (ANGLE_MAPPING_DISTANCE for single scattering, ANGLE_MAPPING_BLENDED for the orders ≥ 2).
layout(local_size_x = 64) in;

#include "atmosphere_common.glsl"
#include "view_ray.glsl"

void main() {
  const int ray = int(gl_GlobalInvocationID.x);
  if (ray >= SCATTERING_R * SCATTERING_MU) return;
  const int z = ray / SCATTERING_MU, y = ray % SCATTERING_MU;
  const ScatteringCoordinates c = scattering_texel_coordinates(0, y, z, VIEW_MAPPING);
  const real d = distance_to_nearest_boundary(c.r, c.mu, c.hits_ground);
  const real lowest = lowest_point_distance(c.r, c.mu, d, c.hits_ground);
  const real stretch = air_mass_stretch(c.r, c.mu);
  real4 optical_depth = real4(0);
  real4 previous_beta = extinction(clamp(c.r, RB, RT) - RB);
  real previous_t = real(0);
  for (int i = 0; i <= SCATTERING_SAMPLES; ++i) {
    const real t = ray_sample_distance(i, SCATTERING_SAMPLES, d, lowest);
    if (i > 0) {
      PRECISE real step = (t - previous_t) / real(OPTICAL_DEPTH_SUBSTEPS);
      for (int k = 1; k <= OPTICAL_DEPTH_SUBSTEPS; ++k) {
        PRECISE real t_k = previous_t + real(k) * step;
        PRECISE real r_k = clamp(sqrt(t_k * t_k + real(2) * c.r * c.mu * t_k + c.r * c.r), RB, RT);
        const real4 beta = extinction(r_k - RB);
        optical_depth += integrate_interval(previous_beta, beta, step);
        previous_beta = beta;
      }
    }
    previous_t = t;
    PRECISE real r_t = clamp(sqrt(t * t + real(2) * c.r * c.mu * t + c.r * c.r), RB, RT);
    PRECISE real mu_t = clamp((c.r * c.mu + t) / r_t, real(-1), real(1));
    const int sample_index = view_ray_sample_index(z, y, i);
    view_transmittance[sample_index] = exp_r4(-stretch * optical_depth);
    view_ray_uv[sample_index] = real2(scattering_u_r(r_t), scattering_u_mu(r_t, mu_t, c.hits_ground, VIEW_MAPPING));
  }
}
