// Inserted by tests/render/shader_faults.cpp at the end of the fp64 elementary
// functions of shaders/atmosphere/maths.glsl, with ULP_PERTURBATION defined
// (tests/render/gpu_precompute_test.cpp, parameterization_gpu_test.cpp).
#if USE_FP64
// sqrt, exp_r and log_r of double moved ULP_PERTURBATION ulp away from zero
// (toward zero when negative), as on a driver whose fp64 sqrt is not correctly
// rounded (NVIDIA 580.159.04: 1 ulp) or whose compiler fuses the series' steps
// into FMAs, so that the bounds of the GPU tests are checked against such
// arithmetic on llvmpipe, whose results are otherwise the CPU's.
double ulps_away(double v) {
  if (v == 0.0LF || isinf(v) || isnan(v)) return v;
  uvec2 b = unpackDouble2x32(v);
  const uint low = b.x;
  if (ULP_PERTURBATION >= 0) {
    b.x = low + uint(ULP_PERTURBATION);
    if (b.x < low) b.y += 1u;
  } else {
    b.x = low - uint(-ULP_PERTURBATION);
    if (b.x > low) b.y -= 1u;
  }
  return packDouble2x32(b);
}
double perturbed_sqrt(double x) { return ulps_away(sqrt(x)); }
dvec2 perturbed_sqrt(dvec2 x) { return dvec2(perturbed_sqrt(x.x), perturbed_sqrt(x.y)); }
dvec3 perturbed_sqrt(dvec3 x) { return dvec3(perturbed_sqrt(x.x), perturbed_sqrt(x.y), perturbed_sqrt(x.z)); }
dvec4 perturbed_sqrt(dvec4 x) {
  return dvec4(perturbed_sqrt(x.x), perturbed_sqrt(x.y), perturbed_sqrt(x.z), perturbed_sqrt(x.w));
}
float perturbed_sqrt(float x) { return sqrt(x); }
vec2 perturbed_sqrt(vec2 x) { return sqrt(x); }
vec3 perturbed_sqrt(vec3 x) { return sqrt(x); }
vec4 perturbed_sqrt(vec4 x) { return sqrt(x); }
double perturbed_exp(double x) { return ulps_away(exp_r(x)); }
double perturbed_log(double x) { return ulps_away(log_r(x)); }
#define sqrt perturbed_sqrt
#define exp_r perturbed_exp
#define log_r perturbed_log
#endif
