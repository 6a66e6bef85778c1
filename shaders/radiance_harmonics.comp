#version 450 core
// Scattering density, step 1 of 3 (harmonics.glsl): for one column (r, μs)
// and one μ node of its horizon-split rule, the incoming radiance of order
// n − 1 (previous_order.glsl, plus the ground's reflection of the irradiance
// of order n − 2 where the direction hits the ground) over 2·HALF_AZIMUTHS
// azimuths, reduced to its cosine moments C_m = ∫ L cos(mφ) dφ (the radiance
// is symmetric about the sun's vertical: the azimuths over (π, 2π) mirror
// those over [0, π)). One group of 4 wavelengths.
layout(local_size_x = 64) in;

#include "atmosphere_common.glsl"
#include "previous_order.glsl"
#include "harmonics.glsl"

#if !FIRST_ORDER
layout(binding = DELTA_IRRADIANCE_UNIT) uniform sampler2D delta_irradiance_texture;
#endif

void main() {
  const int invocation = int(gl_GlobalInvocationID.x);
  if (invocation >= COLUMNS * HARMONIC_NODES) return;
  const int column = invocation / HARMONIC_NODES, node = invocation % HARMONIC_NODES;
  const int z = column / SCATTERING_MU_S, mu_s_index = column % SCATTERING_MU_S;
  const ScatteringCoordinates c = scattering_texel_coordinates(mu_s_index, 0, z, ANGLE_MAPPING_BLENDED);
  const real mu = harmonic_rule_mu(z, node);
  const bool hits_ground = node < SPHERE_ZENITH_SAMPLES;
  PRECISE real sin_theta = sqrt(max(real(0), real(1) - mu * mu));
  PRECISE real sun_x = sqrt(max(real(0), real(1) - c.mu_s * c.mu_s));
  const real3 sun = real3(sun_x, real(0), c.mu_s);
  const real4 albedo = wavelength_field(FIELD_GROUND_ALBEDO);

  ScatteringUV uv;
  uv.u_r = scattering_u_r(c.r);
  uv.u_mu_s = scattering_u_mu_s(c.mu_s, PREVIOUS_ORDER_MAPPING);
  uv.u_mu = scattering_u_mu(c.r, mu, hits_ground, PREVIOUS_ORDER_MAPPING);
  real ground_distance = real(0);
  real4 ground_t = real4(0);
  if (hits_ground) {
    ground_distance = distance_to_bottom(c.r, mu);
    ground_t = transmittance(c.r, mu, ground_distance, true);
  }

  real4 moments[HARMONIC_ORDERS];
  for (int m = 0; m < HARMONIC_ORDERS; ++m) moments[m] = real4(0);
  const real d_phi = PI / real(HALF_AZIMUTHS);
  for (int k = 0; k < HALF_AZIMUTHS; ++k) {
    real sin_phi, cos_phi;
    sincos_r((real(k) + real(0.5)) * d_phi, sin_phi, cos_phi);
    const real3 omega = real3(sin_theta * cos_phi, sin_theta * sin_phi, mu);
    const real nu_i = clamp(dot3(omega, sun), real(-1), real(1));
    uv.u_nu = scattering_u_nu(mu, c.mu_s, nu_i);
    real4 incoming = previous_order_radiance(uv, nu_i);
    if (hits_ground) {
      const real3 ground_normal =
          normalize3(real3(omega.x * ground_distance, omega.y * ground_distance, c.r + omega.z * ground_distance));
      const real mu_s_ground = clamp(dot3(ground_normal, sun), real(-1), real(1));
#if FIRST_ORDER
      const real4 ground_e = transmittance_to_sun(RB, mu_s_ground) * max(mu_s_ground, real(0));
#else
      const real2 e_uv = irradiance_uv(RB, mu_s_ground);
      const real4 ground_e = sample_table_2d(delta_irradiance_texture, IRRADIANCE_MU_S, IRRADIANCE_R, e_uv.x, e_uv.y);
#endif
      incoming += ground_t * albedo / PI * ground_e;
    }
    // cos(mφ) by Chebyshev's recurrence; × 2: the mirrored azimuth 2π − φ.
    real cos_prev = real(1), cos_m = real(1);
    for (int m = 0; m < HARMONIC_ORDERS; ++m) {
      const real w = real(2) * d_phi * cos_m;
      moments[m] += w * incoming;
      const real next = m == 0 ? cos_phi : real(2) * cos_phi * cos_m - cos_prev;
      cos_prev = cos_m;
      cos_m = next;
    }
  }
  for (int m = 0; m < HARMONIC_ORDERS; ++m) azimuth_moments[azimuth_moment_index(column, node, m)] = moments[m];
}
