// The arithmetic under the atmosphere's shaders (included by
// atmosphere_common.glsl, first): the precision (`real`, USE_FP64), double
// exp/log/sin/cos/acos that GLSL lacks and their constants (in double from the
// C++ side), PRECISE, the quadrature rules of atmosphere/lut/quadrature.h and
// the vector helpers of vec3.h. No model data.

// ------------------------------------------------------------ precision

#if USE_FP64
#define real double
#define real2 dvec2
#define real3 dvec3
#define real4 dvec4

// ---- double-precision elementary functions (GLSL has them for float only)

/// Every double constant of fp64 code that is not a small integer or a power of
/// two — the splits of ln 2 and π/2 below (LN2_HI, LN2_LO, INV_LN2, TWO_OVER_PI,
/// PIO2_1, PIO2_1T, SQRT_HALF: fdlibm's) and the model's (PI, INV_4PI, the
/// radii, …) — arrives as the bits of a C++ double in this uniform block,
/// named by the shader model's defines (LN2_HI → fp64_constants[0].x;
/// render/lut/shader_model.cpp). None is a GLSL literal: NVIDIA's compiler
/// (driver 580.159.04) gave fp64 shaders π, 0.7629, 0.932 and 1e-4 rounded to
/// float; a uniform reaches any driver exactly. The series'
/// coefficients below are quotients of integers that float holds exactly up
/// to 13! (and terms beyond r^13 are below 1e-17 of the sum).
layout(std140, binding = FP64_CONSTANTS_BINDING) uniform Fp64Constants { dvec4 fp64_constants[FP64_CONSTANT_VECTORS]; };

/// e^x: x = k ln2 + r with |r| ≤ ln2/2, Taylor series of e^r to r^13 (error < 5e-18), times 2^k.
double exp_r(double x) {
  if (x < -745.2LF) return 0.0LF;
  x = min(x, 709.78LF);
  const double k = floor(x * INV_LN2 + 0.5LF);
  const double r = (x - k * LN2_HI) - k * LN2_LO;
  double p = 1.0LF / 6227020800.0LF;  // 1/13!
  p = p * r + 1.0LF / 479001600.0LF;
  p = p * r + 1.0LF / 39916800.0LF;
  p = p * r + 1.0LF / 3628800.0LF;
  p = p * r + 1.0LF / 362880.0LF;
  p = p * r + 1.0LF / 40320.0LF;
  p = p * r + 1.0LF / 5040.0LF;
  p = p * r + 1.0LF / 720.0LF;
  p = p * r + 1.0LF / 120.0LF;
  p = p * r + 1.0LF / 24.0LF;
  p = p * r + 1.0LF / 6.0LF;
  p = p * r + 0.5LF;
  p = p * r + 1.0LF;
  p = p * r + 1.0LF;
  return ldexp(p, int(k));
}

/// ln x for x > 0: x = m 2^e with m ∈ [√½, √2), ln m = 2 atanh(s), s = (m−1)/(m+1), |s| ≤ 0.172.
double log_r(double x) {
  int e;
  double m = frexp(x, e);
  if (m < SQRT_HALF) {
    m *= 2.0LF;
    e -= 1;
  }
  const double s = (m - 1.0LF) / (m + 1.0LF);
  const double z = s * s;
  double p = 1.0LF / 23.0LF;
  p = p * z + 1.0LF / 21.0LF;
  p = p * z + 1.0LF / 19.0LF;
  p = p * z + 1.0LF / 17.0LF;
  p = p * z + 1.0LF / 15.0LF;
  p = p * z + 1.0LF / 13.0LF;
  p = p * z + 1.0LF / 11.0LF;
  p = p * z + 1.0LF / 9.0LF;
  p = p * z + 1.0LF / 7.0LF;
  p = p * z + 1.0LF / 5.0LF;
  p = p * z + 1.0LF / 3.0LF;
  p = p * z + 1.0LF;
  const double de = double(e);
  return de * LN2_HI + (2.0LF * s * p + de * LN2_LO);
}

/// sin and cos of x (|x| up to a few π): x = k π/2 + r, |r| ≤ π/4, Taylor series to r^19 / r^20.
void sincos_r(double x, out double s, out double c) {
  const double k = floor(x * TWO_OVER_PI + 0.5LF);
  const double r = (x - k * PIO2_1) - k * PIO2_1T;
  const double z = r * r;
  double ps = -1.0LF / 121645100408832000.0LF;  // −1/19!
  ps = ps * z + 1.0LF / 355687428096000.0LF;
  ps = ps * z - 1.0LF / 1307674368000.0LF;
  ps = ps * z + 1.0LF / 6227020800.0LF;
  ps = ps * z - 1.0LF / 39916800.0LF;
  ps = ps * z + 1.0LF / 362880.0LF;
  ps = ps * z - 1.0LF / 5040.0LF;
  ps = ps * z + 1.0LF / 120.0LF;
  ps = ps * z - 1.0LF / 6.0LF;
  const double sin_r = r + r * z * ps;
  double pc = 1.0LF / 2432902008176640000.0LF;  // 1/20!
  pc = pc * z - 1.0LF / 6402373705728000.0LF;
  pc = pc * z + 1.0LF / 20922789888000.0LF;
  pc = pc * z - 1.0LF / 87178291200.0LF;
  pc = pc * z + 1.0LF / 479001600.0LF;
  pc = pc * z - 1.0LF / 3628800.0LF;
  pc = pc * z + 1.0LF / 40320.0LF;
  pc = pc * z - 1.0LF / 720.0LF;
  pc = pc * z + 1.0LF / 24.0LF;
  pc = pc * z - 0.5LF;
  const double cos_r = 1.0LF + z * pc;
  const int quadrant = int(k) & 3;
  if (quadrant == 0) {
    s = sin_r;
    c = cos_r;
  } else if (quadrant == 1) {
    s = cos_r;
    c = -sin_r;
  } else if (quadrant == 2) {
    s = -sin_r;
    c = -cos_r;
  } else {
    s = -cos_r;
    c = sin_r;
  }
}

double cos_r(double x) {
  double s, c;
  sincos_r(x, s, c);
  return c;
}

/// acos x for x ∈ [−1, 1]: θ0 from the float atan of (√(1−x²), x), refined by the
/// angle between (cos θ0, sin θ0) and (x, √(1−x²)): θ = θ0 + atan(u), u ~ 1e-7.
double acos_r(double x) {
  const double y = sqrt((1.0LF - x) * (1.0LF + x));
  const double t0 = double(atan(float(y), float(x)));
  double s0, c0;
  sincos_r(t0, s0, c0);
  const double u = (y * c0 - x * s0) / (x * c0 + y * s0);
  const double u2 = u * u;
  return t0 + u * (1.0LF - u2 * (1.0LF / 3.0LF - u2 * 0.2LF));
}

// A test program inserts its replacement of sqrt, exp_r and log_r after the
// next line (tests/render/shader_faults.h).
// ---- end of the fp64 elementary functions

#else  // float fallback

#define real float
#define real2 vec2
#define real3 vec3
#define real4 vec4
#define exp_r exp
#define log_r log
#define cos_r cos
#define acos_r acos
void sincos_r(float x, out float s, out float c) {
  s = sin(x);
  c = cos(x);
}

#endif

// Geometry in the CPU's operation order: no fused multiply-add or reassociation
// (the mappings have discontinuities, e.g. at the horizon, where one rounding
// difference moves a sample to the other side).
#if USE_FP64
#define PRECISE precise
#else
#define PRECISE
#endif

// ------------------------------------------------------------ quadrature (quadrature.h)

real integrate_interval(real f0, real f1, real h) {
#if QUADRATURE_LOG_LINEAR
  if (f0 <= real(0) || f1 <= real(0)) return real(0.5) * h * (f0 + f1);
  PRECISE real x = log_r(f1 / f0);
  if (abs(x) < SERIES_LIMIT) return h * f0 * (real(1) + x / real(2) + x * x / real(6));
  return h * (f1 - f0) / x;
#else
  return real(0.5) * h * (f0 + f1);
#endif
}

real4 integrate_interval(real4 f0, real4 f1, real h) {
  return real4(integrate_interval(f0.x, f1.x, h), integrate_interval(f0.y, f1.y, h), integrate_interval(f0.z, f1.z, h),
               integrate_interval(f0.w, f1.w, h));
}

// ------------------------------------------------------------ samples along a ray (quadrature.h)

/// Distance from the start of a ray (r, μ) of length d to its lowest point
/// (lowest_point_distance_m).
real lowest_point_distance(real r, real mu, real d, bool hits_ground) {
  if (mu >= real(0)) return real(0);
  if (hits_ground) return d;
  PRECISE real tangent = -r * mu;
  return min(tangent, d);
}

/// t_i of sample i of n along a ray of length d with its lowest point at
/// `lowest`: crowded quadratically toward the lowest point (ray_sample_distance_m).
real ray_sample_distance(int i, int n, real d, real lowest) {
  PRECISE real s = real(i) / real(n);
  PRECISE real s_low = d > real(0) ? clamp(lowest / d, real(0), real(1)) : real(0);
  if (s >= s_low) {
    PRECISE real span = real(1) - s_low;
    if (span <= real(0)) return d;
    PRECISE real u = (s - s_low) / span;
    PRECISE real t = lowest + (d - lowest) * u * u;
    return t;
  }
  PRECISE real u = (s_low - s) / s_low;
  PRECISE real t = lowest - lowest * u * u;
  return t;
}

/// The sample after i when a ray of n intervals is read every `stride`-th
/// sample and at its end (next_ray_sample, quadrature.h).
int next_ray_sample(int i, int stride, int n) { return i >= n ? n + 1 : min(i + stride, n); }
/// The stride of a coarse ray: every sample on a ray that dips to a tangent
/// point and climbs again (coarse_ray_stride_for, quadrature.h).
int coarse_ray_stride_for(real mu, bool ray_hits_ground, int stride) {
  return mu < real(0) && !ray_hits_ground ? 1 : stride;
}

real4 exp_r4(real4 x) { return real4(exp_r(x.x), exp_r(x.y), exp_r(x.z), exp_r(x.w)); }

// ------------------------------------------------------------ vectors (vec3.h), in the CPU's operation order

real dot3(real3 a, real3 b) {
  PRECISE real d = a.x * b.x + a.y * b.y + a.z * b.z;
  return d;
}
real3 normalize3(real3 v) { return v / sqrt(dot3(v, v)); }
