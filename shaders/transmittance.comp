#version 450 core
// Transmittance T(r, μ) to the top of the atmosphere for one group of 4
// wavelengths: T = exp(−s(r, μ) ∫₀^d β_ext(h(t)) dt), composite Simpson rule with
// TRANSMITTANCE_SAMPLES (even) intervals, s the air-mass stretch
// (cpu_precompute.cpp, compute_transmittance).
layout(local_size_x = 8, local_size_y = 8) in;

#include "atmosphere_common.glsl"

layout(binding = OUTPUT_IMAGE, rgba32f) uniform writeonly image2D transmittance_image;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= TRANSMITTANCE_MU || p.y >= TRANSMITTANCE_R) return;
  real r, mu;
  transmittance_r_mu((real(p.x) + real(0.5)) / real(TRANSMITTANCE_MU), (real(p.y) + real(0.5)) / real(TRANSMITTANCE_R),
                     r, mu);
  const real d = distance_to_top(r, mu);
  const real dx = d / real(TRANSMITTANCE_SAMPLES);
  const real w_end = real(1) / real(3), w_odd = real(4) / real(3), w_even = real(2) / real(3);
  real4 tau = real4(0);
  for (int i = 0; i <= TRANSMITTANCE_SAMPLES; ++i) {
    const real t = real(i) * dx;
    PRECISE real r_t = sqrt(t * t + real(2) * r * mu * t + r * r);
    const real4 beta = extinction(r_t - RB);
    const real w = (i == 0 || i == TRANSMITTANCE_SAMPLES) ? w_end : (i % 2 == 1 ? w_odd : w_even);
    tau += w * beta * dx;
  }
  const real stretch = air_mass_stretch(r, mu);
  imageStore(transmittance_image, p, vec4(exp_r4(-stretch * tau)));
}
