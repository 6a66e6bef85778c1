#version 450 core
// The coordinates of the scattering-table texels that the CPU finds by bisection
// (parameterization.cpp: mu_s_from_unit, mu_sky_from_unit), computed once per
// precompute instead of once per texel and stage: μs of every μs index and μ of
// every sky μ index and r layer, for both angle mappings, and acos(μs_min).
// scattering_texel_coordinates() reads them (layout: TEXEL_* in atmosphere_common.glsl).
layout(local_size_x = 64) in;

#include "atmosphere_common.glsl"

void main() {
  const int i = int(gl_GlobalInvocationID.x);
  if (i < TEXEL_SUN_THETA_MAX) {
    const int mapping = i / SCATTERING_MU_S, index = i % SCATTERING_MU_S;
    const real u_mu_s = (real(index) + real(0.5)) / real(SCATTERING_MU_S);
    texel_values[i] = mu_s_from_unit(unit_from_texture_coord(u_mu_s, SCATTERING_MU_S), mapping);
  } else if (i == TEXEL_SUN_THETA_MAX) {
    texel_values[i] = acos_r(min_sun_cosine());
  } else if (i < TEXEL_VALUE_COUNT) {
    const int half_mu = SCATTERING_MU / 2;
    const int k = i - TEXEL_MU_SKY;
    const int mapping = k / (SCATTERING_R * half_mu), z = (k / half_mu) % SCATTERING_R, y = half_mu + k % half_mu;
    real rho;
    const real r = texel_r(z, rho);
    texel_values[i] = mu_sky_from_unit(r, texel_unit_mu_sky(y), mapping);
  }
}
