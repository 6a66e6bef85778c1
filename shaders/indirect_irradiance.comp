#version 450 core
// Sky irradiance of order n−1 on a horizontal surface, E(r, μs) = ∫ L_{n−1} cos θ dω
// over the upper hemisphere, for one group of 4 wavelengths; written as the
// delta of this order and added to the irradiance table
// (cpu_precompute.cpp, compute_indirect_irradiance).
layout(local_size_x = 8, local_size_y = 8) in;

#include "atmosphere_common.glsl"
#include "previous_order.glsl"

layout(binding = OUTPUT_IMAGE, rgba32f) uniform writeonly image2D delta_irradiance_image;
layout(binding = SECOND_OUTPUT_IMAGE, rgba32f) uniform image2D irradiance_image;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= IRRADIANCE_MU_S || p.y >= IRRADIANCE_R) return;
  real r, mu_s;
  irradiance_r_mu_s((real(p.x) + real(0.5)) / real(IRRADIANCE_MU_S), (real(p.y) + real(0.5)) / real(IRRADIANCE_R), r,
                    mu_s);
  const real3 sun = real3(sqrt(max(real(0), real(1) - mu_s * mu_s)), real(0), mu_s);
  // Gauss–Legendre in μ ∈ [0, 1] (HEMISPHERE_ZENITH_SAMPLES nodes at HEMISPHERE_RULE), uniform in φ.
  const int n_theta = HEMISPHERE_ZENITH_SAMPLES, n_phi = 4 * HEMISPHERE_ZENITH_SAMPLES;
  const real d_phi = real(2) * PI / real(n_phi);
  // Texture coordinates of the incoming radiance: r and μs are those of the texel.
  ScatteringUV uv;
  uv.u_r = scattering_u_r(r);
  uv.u_mu_s = scattering_u_mu_s(mu_s, PREVIOUS_ORDER_MAPPING);
  real4 e = real4(0);
  for (int it = 0; it < n_theta; ++it) {
    PRECISE real mu = real(0.5) + real(0.5) * table_data[HEMISPHERE_RULE + it];  // [−1, 1] → [0, 1]
    PRECISE real sin_theta = sqrt(max(real(0), real(1) - mu * mu));
    const real weight = table_data[HEMISPHERE_RULE + n_theta + it];
    uv.u_mu = scattering_u_mu(r, mu, ray_hits_ground(r, mu), PREVIOUS_ORDER_MAPPING);
    for (int ip = 0; ip < n_phi; ++ip) {
      real sin_phi, cos_phi;
      sincos_r((real(ip) + real(0.5)) * d_phi, sin_phi, cos_phi);
      const real3 omega = real3(sin_theta * cos_phi, sin_theta * sin_phi, mu);
      const real nu = clamp(dot3(omega, sun), real(-1), real(1));
      uv.u_nu = scattering_u_nu(mu, mu_s, nu);
      const real4 incoming = previous_order_radiance(uv, nu);
      const real w = mu * real(0.5) * weight * d_phi;
      e += incoming * w;
    }
  }
  imageStore(delta_irradiance_image, p, vec4(e));
  imageStore(irradiance_image, p, imageLoad(irradiance_image, p) + vec4(e));
}
