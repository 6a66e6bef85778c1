// The radiance of order n−1 arriving from a direction, for the scattering density
// and sky irradiance of order n (cpu_precompute.cpp, previous_order_radiance).
// Needs atmosphere_common.glsl.
//   FIRST_ORDER 1 (n = 2): the single-scattering tables with their phase functions,
//                          read geometrically in μs like every read of a final table;
//   FIRST_ORDER 0 (n ≥ 3): the multiple-scattering table of the last order, also
//                          geometric in μs.
// Each is read with its own angle mapping, PREVIOUS_ORDER_MAPPING. The caller
// computes the texture coordinates (scattering_u_r, scattering_u_mu,
// scattering_u_mu_s, scattering_u_nu with PREVIOUS_ORDER_MAPPING), each in the loop
// where it changes: in a sphere integral r and μs are fixed, μ per zenith step.
#if FIRST_ORDER
const int PREVIOUS_ORDER_MAPPING = ANGLE_MAPPING_DISTANCE;
layout(binding = SINGLE_RAYLEIGH_UNIT) uniform sampler3D single_rayleigh_texture;
#if HAS_MIE
layout(binding = SINGLE_MIE_UNIT) uniform sampler3D single_mie_texture;
#endif
#else
const int PREVIOUS_ORDER_MAPPING = ANGLE_MAPPING_BLENDED;
layout(binding = DELTA_RADIANCE_UNIT) uniform sampler3D delta_radiance_texture;
#endif

/// `uv`: scattering_uvwz(r, μ, μs, ν) with PREVIOUS_ORDER_MAPPING; ν for the phase functions.
real4 previous_order_radiance(ScatteringUV uv, real nu) {
#if FIRST_ORDER
  real4 radiance = sample_scattering_table_geometric_mu_s(single_rayleigh_texture, uv) * rayleigh_phase(nu);
#if HAS_MIE
  radiance = radiance + sample_scattering_table_geometric_mu_s(single_mie_texture, uv) * model_mie_phase(nu);
#endif
  return radiance;
#else
  return sample_scattering_table_geometric_mu_s(delta_radiance_texture, uv);
#endif
}
