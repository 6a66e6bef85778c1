#version 450 core
// T(x, y_i) and (u_r, u_μ) at the samples of each view ray of the scattering table
// (view_ray.glsl) for one group of 4 wavelengths; T from the transmittance table
// (cpu_precompute.cpp: view_ray_transmittance, the same operations in the same order).
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
  const real dx = d / real(SCATTERING_SAMPLES);
  for (int i = 0; i <= SCATTERING_SAMPLES; ++i) {
    const real t = real(i) * dx;
    PRECISE real r_t = clamp(sqrt(t * t + real(2) * c.r * c.mu * t + c.r * c.r), RB, RT);
    PRECISE real mu_t = clamp((c.r * c.mu + t) / r_t, real(-1), real(1));
    const int sample_index = view_ray_sample_index(z, y, i);
    view_transmittance[sample_index] = transmittance(c.r, c.mu, t, c.hits_ground);
    view_ray_uv[sample_index] = real2(scattering_u_r(r_t), scattering_u_mu(r_t, mu_t, c.hits_ground, VIEW_MAPPING));
  }
}
