#version 450 core
// Scattering density J_n(r, μ, μs, ν) = ∫_4π [β_R ρ_R P_R + β_M ρ_M P_M] L_{n−1} dω
// for one group of 4 wavelengths, where L_{n−1} includes, in directions that hit
// the ground, the ground's reflection of the irradiance of order n−2 (the direct
// sun for n = 2, FIRST_ORDER) (cpu_precompute.cpp, compute_scattering_density).
// SPHERE_ZENITH_SAMPLES Gauss–Legendre nodes in cos θ, twice as many azimuths.
layout(local_size_x = 8, local_size_y = 8) in;

#include "atmosphere_common.glsl"
#include "previous_order.glsl"

layout(binding = OUTPUT_IMAGE, rgba32f) uniform writeonly image3D density_image;
#if !FIRST_ORDER
layout(binding = DELTA_IRRADIANCE_UNIT) uniform sampler2D delta_irradiance_texture;
#endif

void main() {
  const ivec3 p = ivec3(gl_GlobalInvocationID.xy, z_offset + int(gl_GlobalInvocationID.z));
  if (p.x >= SCATTERING_NU * SCATTERING_MU_S || p.y >= SCATTERING_MU || p.z >= SCATTERING_R) return;
  const ScatteringCoordinates c = scattering_texel_coordinates(p.x, p.y, p.z, ANGLE_MAPPING_BLENDED);
  // Local frame: zenith z, view in the xz-plane, sun from μs and ν.
  const real3 view = real3(sqrt(max(real(0), real(1) - c.mu * c.mu)), real(0), c.mu);
  PRECISE real sun_x = view.x == real(0) ? real(0) : (c.nu - c.mu * c.mu_s) / view.x;
  PRECISE real sun_y = sqrt(max(real(1) - sun_x * sun_x - c.mu_s * c.mu_s, real(0)));
  const real3 sun = real3(sun_x, sun_y, c.mu_s);
  const real h = c.r - RB;
  const real4 rayleigh = wavelength_field(FIELD_RAYLEIGH_SCATTERING) * rayleigh_density(h);
#if HAS_MIE
  const real rho_m = mie_density(h);
  const real4 mie_scattering = wavelength_field(FIELD_MIE_SCATTERING);
#endif
  const real4 albedo = wavelength_field(FIELD_GROUND_ALBEDO);
  // Texture coordinates of the incoming radiance: r and μs are those of the texel.
  ScatteringUV uv;
  uv.u_r = scattering_u_r(c.r);
  uv.u_mu_s = scattering_u_mu_s(c.mu_s, PREVIOUS_ORDER_MAPPING);

  // Directions: Gauss–Legendre in μ = cos θ (nodes and weights from gauss_legendre.h
  // in TableData at SPHERE_RULE), uniform in φ. cos φ, sin φ are recomputed per
  // direction: an array of them indexed by the loop counter makes the compiler
  // unroll the whole loop (~10 s of LLVM compile on llvmpipe).
  const int n_theta = SPHERE_ZENITH_SAMPLES, n_phi = 2 * SPHERE_ZENITH_SAMPLES;
  const real d_phi = real(2) * PI / real(n_phi);

  real4 j = real4(0);
  for (int it = 0; it < n_theta; ++it) {
    const real cos_theta = table_data[SPHERE_RULE + it];
    PRECISE real sin_theta = sqrt(max(real(0), real(1) - cos_theta * cos_theta));
    const bool hits_ground = ray_hits_ground(c.r, cos_theta);
    uv.u_mu = scattering_u_mu(c.r, cos_theta, hits_ground, PREVIOUS_ORDER_MAPPING);
    // Ground seen in this direction: distance and transmittance.
    real ground_distance = real(0);
    real4 ground_t = real4(0);
    if (hits_ground) {
      ground_distance = distance_to_bottom(c.r, cos_theta);
      ground_t = transmittance(c.r, cos_theta, ground_distance, true);
    }
    const real d_omega = table_data[SPHERE_RULE + n_theta + it] * d_phi;
    for (int ip = 0; ip < n_phi; ++ip) {
      real sin_phi, cos_phi;
      sincos_r((real(ip) + real(0.5)) * d_phi, sin_phi, cos_phi);
      const real3 omega = real3(sin_theta * cos_phi, sin_theta * sin_phi, cos_theta);
      const real nu_i = clamp(dot3(omega, sun), real(-1), real(1));
      uv.u_nu = scattering_u_nu(cos_theta, c.mu_s, nu_i);
      real4 incoming = previous_order_radiance(uv, nu_i);
      if (hits_ground) {
        // zenith · r + ω · d, with the CPU's zero products folded.
        const real3 ground_normal =
            normalize3(real3(omega.x * ground_distance, omega.y * ground_distance, c.r + omega.z * ground_distance));
        const real mu_s_ground = clamp(dot3(ground_normal, sun), real(-1), real(1));
#if FIRST_ORDER
        const real4 ground_e = transmittance_to_sun(RB, mu_s_ground) * max(mu_s_ground, real(0));
#else
        const real2 uv = irradiance_uv(RB, mu_s_ground);
        const real4 ground_e = sample_table_2d(delta_irradiance_texture, IRRADIANCE_MU_S, IRRADIANCE_R, uv.x, uv.y);
#endif
        incoming += ground_t * albedo / PI * ground_e;
      }
      const real cos_scatter = clamp(dot3(view, omega), real(-1), real(1));
      real4 beta = rayleigh * rayleigh_phase(cos_scatter);
#if HAS_MIE
      beta = beta + mie_scattering * rho_m * model_mie_phase(cos_scatter);
#endif
      j += incoming * beta * d_omega;
    }
  }
  imageStore(density_image, p, vec4(j));
}
