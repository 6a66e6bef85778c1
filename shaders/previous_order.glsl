// The radiance of order n−1 arriving from a direction, for the scattering density
// and sky irradiance of order n (cpu_precompute.cpp, previous_order_radiance).
// Needs atmosphere_common.glsl.
//   first_order ≠ 0 (n = 2): the single-scattering tables with their phase functions,
//                            read geometrically in μs like every read of a final table;
//   first_order = 0 (n ≥ 3): the multiple-scattering table of the last order.
// A uniform, not a #define: one program serves every order (one build less per
// shader; the branch is the same for every invocation of a dispatch).
// Each is read with its own angle mapping, PREVIOUS_ORDER_MAPPING. The caller
// computes the texture coordinates (scattering_u_r, scattering_u_mu,
// scattering_u_mu_s, scattering_u_nu with PREVIOUS_ORDER_MAPPING), each in the loop
// where it changes: in a sphere integral r and μs are fixed, μ per zenith step.
uniform int first_order;
#define PREVIOUS_ORDER_MAPPING (first_order != 0 ? ANGLE_MAPPING_DISTANCE : ANGLE_MAPPING_BLENDED)
layout(binding = SINGLE_RAYLEIGH_UNIT) uniform sampler3D single_rayleigh_texture;
#if HAS_MIE
layout(binding = SINGLE_MIE_UNIT) uniform sampler3D single_mie_texture;
#endif
layout(binding = DELTA_RADIANCE_UNIT) uniform sampler3D delta_radiance_texture;

/// `uv`: scattering_uvwz(r, μ, μs, ν) with PREVIOUS_ORDER_MAPPING; ν for the phase functions.
real4 previous_order_radiance(ScatteringUV uv, real nu) {
  if (first_order == 0) return sample_scattering_table(delta_radiance_texture, uv);
  real4 radiance = sample_scattering_table_geometric_mu_s(single_rayleigh_texture, uv) * rayleigh_phase(nu);
#if HAS_MIE
  radiance = radiance + sample_scattering_table_geometric_mu_s(single_mie_texture, uv) * model_mie_phase(nu);
#endif
  return radiance;
}

