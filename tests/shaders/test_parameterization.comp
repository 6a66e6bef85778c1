#version 450 core
// The table parameterization of atmosphere_common.glsl evaluated for a list of
// inputs, for tests/render/parameterization_gpu_test.cpp, which compares every
// value with the C++ functions of atmosphere/lut/parameterization.h at the
// same inputs. Compiled with the shader model's defines (render/lut/shader_model.h),
// the model's buffers bound as for the precompute, and the texel coordinates
// filled by texel_coordinates.comp (scattering_u_mu_s reads acos(μs_min) there).
//
// Defines (the test's, besides the shader model's):
//   CASES_BINDING, RESULTS_BINDING   storage bindings of the two buffers below
//   CASE_STRIDE, RESULT_STRIDE       reals per case and per result
// Uniforms: case_count; mode 0: the functions of one (r, μ, μs, ν) case each,
// mode 1: scattering_texel_coordinates of the texel of index i.
layout(local_size_x = 64) in;

#include "atmosphere_common.glsl"

/// Mode 0, per case: r, μ, μs, ν, hits_ground (0/1), angle mapping, then the
/// inverse functions' inputs: u_μ, v_r (transmittance), u_μs, v_r (irradiance), x_ν.
/// Mode 1: x, y, z, angle mapping of a scattering texel.
layout(std430, binding = CASES_BINDING) readonly buffer Cases { real cases[]; };
layout(std430, binding = RESULTS_BINDING) writeonly buffer Results { real results[]; };
uniform int case_count;
uniform int mode;

void main() {
  const int i = int(gl_GlobalInvocationID.x);
  if (i >= case_count) return;
  const int in_base = i * CASE_STRIDE, out_base = i * RESULT_STRIDE;
  if (mode == 1) {
    const ScatteringCoordinates c = scattering_texel_coordinates(int(cases[in_base]), int(cases[in_base + 1]),
                                                                 int(cases[in_base + 2]), int(cases[in_base + 3]));
    results[out_base] = c.r;
    results[out_base + 1] = c.mu;
    results[out_base + 2] = c.mu_s;
    results[out_base + 3] = c.nu;
    results[out_base + 4] = c.hits_ground ? real(1) : real(0);
    return;
  }
  const real r = cases[in_base], mu = cases[in_base + 1], mu_s = cases[in_base + 2], nu = cases[in_base + 3];
  const bool hits_ground = cases[in_base + 4] != real(0);
  const int mapping = int(cases[in_base + 5]);

  const real2 t = transmittance_uv(r, mu);
  real t_r, t_mu;
  transmittance_r_mu(cases[in_base + 6], cases[in_base + 7], t_r, t_mu);
  const real2 e = irradiance_uv(r, mu_s);
  real e_r, e_mu_s;
  irradiance_r_mu_s(cases[in_base + 8], cases[in_base + 9], e_r, e_mu_s);
  const ScatteringUV s = scattering_uvwz(r, mu, mu_s, nu, hits_ground, mapping);

  results[out_base] = t.x;
  results[out_base + 1] = t.y;
  results[out_base + 2] = t_r;
  results[out_base + 3] = t_mu;
  results[out_base + 4] = e.x;
  results[out_base + 5] = e.y;
  results[out_base + 6] = e_r;
  results[out_base + 7] = e_mu_s;
  results[out_base + 8] = s.u_nu;
  results[out_base + 9] = s.u_mu_s;
  results[out_base + 10] = s.u_mu;
  results[out_base + 11] = s.u_r;
  results[out_base + 12] = scattering_u_r(r);
  results[out_base + 13] = scattering_u_mu(r, mu, hits_ground, mapping);
  results[out_base + 14] = scattering_u_mu_s(mu_s, mapping);
  results[out_base + 15] = scattering_u_nu(mu, mu_s, nu);
  results[out_base + 16] = scattering_nu_from_unit(mu, mu_s, cases[in_base + 10]);
  results[out_base + 17] = ray_hits_ground(r, mu) ? real(1) : real(0);
  results[out_base + 18] = min_sun_cosine();
}
