// Shared code of the lookup-table precomputation on the GPU
// (render/lut/gpu_precompute.cpp). Every function mirrors, operation for
// operation, the CPU implementation in atmosphere/lut/ (parameterization.cpp,
// table.cpp, lookup_tables.cpp, quadrature.h, cpu_precompute.cpp) and
// atmosphere/ (density_profile.cpp, phase_functions.cpp, air_mass.cpp), so the
// two paths produce the same tables (bit-identical on Mesa llvmpipe). Expressions
// keep the CPU's evaluation order (a · b · c is (a · b) · c, as in C++), and
// geometry is PRECISE (no fused multiply-add): change both sides together.
//
// Precision (USE_FP64): 1 runs geometry, quadrature sums and table
// interpolation in double, like the CPU. GLSL has no double exp/log/sin/cos/acos,
// so this file implements them (exp_r, log_r, sincos_r/cos_r, acos_r below,
// within a few ulp of the C library). 0 is the float fallback: every `real` is a
// float and the built-in functions are used. Tables are float32 either way.
//
// Wavelengths: one dispatch handles one group of 4 wavelengths (`wavelength_group`),
// so every radiance is a real4; the tables of group g are RGBA32F textures holding
// wavelengths 4g..4g+3 (unused lanes of the last group have zero coefficients).
//
// Defines set by the C++ side (all required):
//   USE_FP64                               1: double, 0: float
//   BOTTOM_RADIUS, TOP_RADIUS              metres (literals of type real)
//   TRANSMITTANCE_MU, TRANSMITTANCE_R, IRRADIANCE_MU_S, IRRADIANCE_R,
//   SCATTERING_R, SCATTERING_MU, SCATTERING_MU_S, SCATTERING_NU   table sizes
//   GEOMETRIC_BLEND_FULL_LOG_RATIO                                 float literal (lookup_tables.h)
//   RAYLEIGH_PHASE                         0 classic, 1 Penndorf, 2 depolarized
//   RAYLEIGH_DEPOLARIZATION                δ (literal; used by RAYLEIGH_PHASE 2)
//   HAS_MIE                                0 drops every Mie term
//   MIE_PHASE                              0 Henyey–Greenstein, 1 double HG, 2 Cornette–Shanks
//   ABSORBER_COUNT                         0 drops the absorber loop
//   AIR_MASS                               0 drops the air-mass stretch
//   WAVELENGTH_FIELDS                      real4s per wavelength group in WavelengthData
//   RAYLEIGH_PROFILE, MIE_PROFILE, AIR_MASS_PROFILE, ABSORBER_PROFILES
//                                          offsets of profile descriptors in TableData
//   AIR_MASS_GROUND_RADIUS, AIR_MASS_TABLE, AIR_MASS_TABLE_SIZE   the stretch table
//   QUADRATURE_LOG_LINEAR                  1: log-linear interval rule, 0: trapezoid
//   SCATTERING_SAMPLES, TRANSMITTANCE_SAMPLES (even)
//   SPHERE_ZENITH_SAMPLES, SPHERE_RULE     Gauss–Legendre rule of the scattering density
//   HEMISPHERE_ZENITH_SAMPLES, HEMISPHERE_RULE   and of the sky irradiance (nodes, weights in TableData)
//   PI, INV_4PI, PENNDORF_A, PENNDORF_B, SERIES_LIMIT   literals of type real: core/units.h,
//                                          atmosphere/phase_functions.h, atmosphere/lut/quadrature.h
//   FIELD_*                                real4 fields of WavelengthData (shader_model.cpp)
//   TEXEL_MU_S, TEXEL_SUN_THETA_MAX, TEXEL_MU_SKY, TEXEL_VALUE_COUNT   TexelCoordinates layout
// and, for every shader loaded from shaders/, the binding points (*_BINDING,
// *_UNIT, *_IMAGE) of render/shader_bindings.h.

// ------------------------------------------------------------ precision

#if USE_FP64
#define real double
#define real2 dvec2
#define real3 dvec3
#define real4 dvec4

// ---- double-precision elementary functions (GLSL has them for float only)

const double LN2_HI = 6.93147180369123816490e-01LF;  // ln 2 split so that k·LN2_HI is exact (fdlibm)
const double LN2_LO = 1.90821492927058770002e-10LF;
const double INV_LN2 = 1.44269504088896338700e+00LF;
const double TWO_OVER_PI = 6.36619772367581382433e-01LF;
const double PIO2_1 = 1.57079632673412561417e+00LF;   // first 33 bits of π/2
const double PIO2_1T = 6.07710050650619224932e-11LF;  // π/2 − PIO2_1
const double SQRT_HALF = 7.07106781186547524401e-01LF;

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

#ifdef ULP_PERTURBATION
// Tests only (tests/render/gpu_precompute_test.cpp, parameterization_gpu_test.cpp):
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

// ------------------------------------------------------------ model data

/// Per wavelength group g, WAVELENGTH_FIELDS real4s from g·WAVELENGTH_FIELDS
/// (the FIELD_* indices, defined by the shader model), one lane per wavelength.
layout(std430, binding = WAVELENGTH_DATA_BINDING) readonly buffer WavelengthData { real4 wavelength_data[]; };
/// Profile descriptors (kind, scale height, first knot, knot count), spline
/// knots (x[], y[], slope[]), the direction quadratures (nodes[], weights[]) and
/// the air-mass table (cos zenith[], stretch[]).
layout(std430, binding = TABLE_DATA_BINDING) readonly buffer TableData { real table_data[]; };

uniform int wavelength_group;

real4 wavelength_field(int field) { return wavelength_data[wavelength_group * WAVELENGTH_FIELDS + field]; }

// ------------------------------------------------------------ density profiles (density_profile.cpp)

/// MonotoneCubicSpline::operator(): held end values outside the knots, cubic Hermite between.
real spline_value(int first, int count, real x) {
  const int xs = first, ys = first + count, ds = first + 2 * count;
  if (x <= table_data[xs]) return table_data[ys];
  if (x >= table_data[xs + count - 1]) return table_data[ys + count - 1];
  // upper_bound: the first knot > x, minus one.
  int lo = 0, n = count;
  while (n > 0) {
    const int step = n / 2;
    if (!(x < table_data[xs + lo + step])) {
      lo += step + 1;
      n -= step + 1;
    } else {
      n = step;
    }
  }
  const int i = lo - 1;
  const real x0 = table_data[xs + i], x1 = table_data[xs + i + 1];
  const real h = x1 - x0;
  const real t = (x - x0) / h;
  const real t2 = t * t, t3 = t2 * t;
  const real h00 = real(2) * t3 - real(3) * t2 + real(1), h10 = t3 - real(2) * t2 + t,
             h01 = real(-2) * t3 + real(3) * t2, h11 = t3 - t2;
  return h00 * table_data[ys + i] + h10 * h * table_data[ds + i] + h01 * table_data[ys + i + 1] +
         h11 * h * table_data[ds + i + 1];
}

/// DensityProfile::operator() of the descriptor at `profile` in TableData.
real profile_density(int profile, real altitude_m) {
  if (table_data[profile] == real(0)) return exp_r(-altitude_m / table_data[profile + 1]);
  return max(real(0), spline_value(int(table_data[profile + 2]), int(table_data[profile + 3]), altitude_m));
}

real rayleigh_density(real h) { return profile_density(RAYLEIGH_PROFILE, h); }
#if HAS_MIE
real mie_density(real h) { return profile_density(MIE_PROFILE, h); }
#endif

/// AtmosphereModel::extinction_m1: β_R ρ_R + β_M^ext ρ_M + Σ β_a ρ_a (no air-mass stretch).
real4 extinction(real h) {
  real4 e = wavelength_field(FIELD_RAYLEIGH_SCATTERING) * rayleigh_density(h);
#if HAS_MIE
  e = e + wavelength_field(FIELD_MIE_EXTINCTION) * mie_density(h);
#endif
#if ABSORBER_COUNT > 0
  for (int a = 0; a < ABSORBER_COUNT; ++a)
    e += wavelength_field(FIELD_ABSORBERS + a) * profile_density(ABSORBER_PROFILES + 4 * a, h);
#endif
  return e;
}

// ------------------------------------------------------------ air mass (air_mass.cpp)

/// AirMassStretch::operator(): the stretch s of the optical depth of the ray through (r, μ).
real air_mass_stretch(real r, real mu) {
#if AIR_MASS
  const real R = AIR_MASS_GROUND_RADIUS;
  const real p = r * sqrt(max(real(0), real(1) - mu * mu));
  if (p < R) {
    // interpolate(stretch_, √(1 − (p/R)²)): abscissae μ_i = t_i², t uniform.
    const real cz = sqrt(real(1) - (p / R) * (p / R));
    const real m = clamp(cz, real(0), real(1));
    const real x = sqrt(m) * real(AIR_MASS_TABLE_SIZE - 1);
    const int i = min(int(x), AIR_MASS_TABLE_SIZE - 2);
    const real c0 = table_data[AIR_MASS_TABLE + i], c1 = table_data[AIR_MASS_TABLE + i + 1];
    const real f = (m - c0) / (c1 - c0);
    const real s0 = table_data[AIR_MASS_TABLE + AIR_MASS_TABLE_SIZE + i];
    const real s1 = table_data[AIR_MASS_TABLE + AIR_MASS_TABLE_SIZE + i + 1];
    return s0 + f * (s1 - s0);
  }
  return real(1) + (table_data[AIR_MASS_TABLE + AIR_MASS_TABLE_SIZE] - real(1)) *
                       profile_density(AIR_MASS_PROFILE, p - R);
#else
  return real(1);
#endif
}

// ------------------------------------------------------------ phase functions (phase_functions.cpp)

real rayleigh_phase(real c) {
#if RAYLEIGH_PHASE == 0
  return real(0.75) * (real(1) + c * c) * INV_4PI;
#elif RAYLEIGH_PHASE == 1
  return PENNDORF_A * (real(1) + PENNDORF_B * c * c) * INV_4PI;
#else
  const real delta = RAYLEIGH_DEPOLARIZATION;
  const real gamma = delta / (real(2) - delta);
  return real(3) / (real(4) * (real(1) + real(2) * gamma)) * ((real(1) + real(3) * gamma) + (real(1) - gamma) * c * c) *
         INV_4PI;
#endif
}

#if HAS_MIE
real4 henyey_greenstein(real c, real4 g) {
  const real4 denom = real(1) + g * g - real(2) * g * c;
  return (real(1) - g * g) / (denom * sqrt(denom)) * INV_4PI;
}

/// MiePhase: P_M(cos θ) for the 4 wavelengths of the group.
real4 mie_phase(real c) {
  const real4 g1 = wavelength_field(FIELD_MIE_G1);
#if MIE_PHASE == 0
  return henyey_greenstein(c, g1);
#elif MIE_PHASE == 1
  const real4 alpha = wavelength_field(FIELD_MIE_ALPHA);
  return alpha * henyey_greenstein(c, g1) + (real(1) - alpha) * henyey_greenstein(c, wavelength_field(FIELD_MIE_G2));
#else
  const real4 denom = real(1) + g1 * g1 - real(2) * g1 * c;
  return real(3) * (real(1) - g1 * g1) * (real(1) + c * c) / (real(2) * (real(2) + g1 * g1) * denom * sqrt(denom)) *
         INV_4PI;
#endif
}
#endif

// ------------------------------------------------------------ geometry (parameterization.cpp)

const real RB = BOTTOM_RADIUS;
const real RT = TOP_RADIUS;

real clamp_cosine(real mu) { return clamp(mu, real(-1), real(1)); }
real safe_sqrt(real a) { return sqrt(max(a, real(0))); }
/// a² − b² as (a − b)(a + b): r − RB is exact near the ground, where r² − RB²
/// cancels (difference_of_squares, parameterization.cpp: in float, 1 m above
/// Mars' ground, r² − RB² is 6 ulp of r² and u_μ at the horizon was off by 0.2).
real difference_of_squares(real a, real b) {
  PRECISE real d = (a - b) * (a + b);
  return d;
}

real horizon_distance_at_top() {
  PRECISE real h = safe_sqrt(difference_of_squares(RT, RB));
  return h;
}
real horizon_distance(real r) {
  PRECISE real rho = safe_sqrt(difference_of_squares(r, RB));
  return rho;
}
/// r from ρ, the inverse of horizon_distance (radius_from_horizon_distance):
/// exactly RB at ρ = 0, at most RT. A correctly rounded sqrt gives the first by
/// itself; NVIDIA's fp64 sqrt (driver 580.159.04) is 1 ulp off there, which made
/// r − RB = 9e-10 m at the ground layer and its ground-hitting texels μ ≈ 0
/// instead of −1; at ρ = H, 1 ulp above RT makes d_min < 0 and μ = 1 come out ≈ 0.
real radius_from_horizon_distance(real rho) {
  PRECISE real r = rho == real(0) ? RB : min(sqrt(rho * rho + RB * RB), RT);
  return r;
}
/// μs_min = cos(90° + 3α) = −sin 3α, α = acos(rb/rt), −1 when 3α ≥ 90°: below
/// that sun no point of any ray in the shell is lit (the 3α argument is at
/// ShellGeometry::min_sun_cosine, parameterization.cpp). With s = sin α = H/rt,
/// sin 3α = 3s − 4s³ (the same arithmetic as the CPU).
real min_sun_cosine() {
  PRECISE real s = horizon_distance_at_top() / RT;
  PRECISE real mu_s = s >= real(0.5) ? real(-1) : -(real(3) * s - real(4) * s * s * s);
  return mu_s;
}

real distance_to_top(real r, real mu) {
  PRECISE real r_mu = r * mu;
  PRECISE real disc = r_mu * r_mu - difference_of_squares(r, RT);
  PRECISE real d = max(real(0), -r_mu + safe_sqrt(disc));
  return d;
}

real distance_to_bottom(real r, real mu) {
  PRECISE real r_mu = r * mu;
  PRECISE real disc = r_mu * r_mu - difference_of_squares(r, RB);
  PRECISE real d = max(real(0), -r_mu - safe_sqrt(disc));
  return d;
}

bool ray_hits_ground(real r, real mu) {
  PRECISE real r_mu = r * mu;
  PRECISE real disc = r_mu * r_mu - difference_of_squares(r, RB);
  return mu < real(0) && disc >= real(0);
}

real distance_to_nearest_boundary(real r, real mu, bool hits_ground) {
  return hits_ground ? distance_to_bottom(r, mu) : distance_to_top(r, mu);
}

real texture_coord_from_unit(real x, int n) {
  PRECISE real u = real(0.5) / real(n) + x * (real(1) - real(1) / real(n));
  return u;
}
real unit_from_texture_coord(real u, int n) {
  PRECISE real x = (u - real(0.5) / real(n)) / (real(1) - real(1) / real(n));
  return x;
}

// ---- transmittance T(r, μ)

real2 transmittance_uv(real r, real mu) {
  PRECISE real H = horizon_distance_at_top();
  PRECISE real rho = horizon_distance(r);
  PRECISE real d = distance_to_top(r, mu);
  PRECISE real d_min = RT - r, d_max = rho + H;
  PRECISE real x_mu = d_max > d_min ? (d - d_min) / (d_max - d_min) : real(0);
  return real2(texture_coord_from_unit(clamp(x_mu, real(0), real(1)), TRANSMITTANCE_MU),
               texture_coord_from_unit(clamp(rho / H, real(0), real(1)), TRANSMITTANCE_R));
}

void transmittance_r_mu(real u_mu, real v_r, out real r_out, out real mu_out) {
  PRECISE real H = horizon_distance_at_top();
  PRECISE real rho = H * unit_from_texture_coord(v_r, TRANSMITTANCE_R);
  PRECISE real r = radius_from_horizon_distance(rho);
  PRECISE real d_min = RT - r, d_max = rho + H;
  PRECISE real d = d_min + unit_from_texture_coord(u_mu, TRANSMITTANCE_MU) * (d_max - d_min);
  PRECISE real mu = d == real(0) ? real(1) : clamp_cosine((H * H - rho * rho - d * d) / (real(2) * r * d));
  r_out = r;
  mu_out = mu;
}

// ---- irradiance E(r, μs)

real2 irradiance_uv(real r, real mu_s) {
  PRECISE real x_r = (r - RB) / (RT - RB);
  return real2(texture_coord_from_unit(clamp(real(0.5) * mu_s + real(0.5), real(0), real(1)), IRRADIANCE_MU_S),
               texture_coord_from_unit(clamp(x_r, real(0), real(1)), IRRADIANCE_R));
}

void irradiance_r_mu_s(real u_mu_s, real v_r, out real r, out real mu_s) {
  PRECISE real r_value = RB + unit_from_texture_coord(v_r, IRRADIANCE_R) * (RT - RB);
  PRECISE real mu_s_value = clamp_cosine(real(2) * unit_from_texture_coord(u_mu_s, IRRADIANCE_MU_S) - real(1));
  r = r_value;
  mu_s = mu_s_value;
}

// ---- scattering S(r, μ, μs, ν), 4D packed into 3D: x = ν index · SCATTERING_MU_S + μs, y = μ, z = r

/// How μ (rays that do not hit the ground) and μs are mapped in a 4D table
/// (AngleMapping of parameterization.h): the single-scattering tables use
/// Bruneton's distance mapping, the multiple-scattering ones (density, delta,
/// multiple) its average with a mapping uniform in angle.
const int ANGLE_MAPPING_DISTANCE = 0;
const int ANGLE_MAPPING_BLENDED = 1;

/// Texel-coordinate values computed once per precompute by texel_coordinates.comp:
/// μs of each μs index per mapping, acos(μs_min), then μ of each sky (upper-half)
/// μ index per mapping and r layer. Offsets (TexelCoordinateLayout of
/// render/lut/shader_model.h, defined by the shader model): TEXEL_MU_S
/// [mapping][μs index], TEXEL_SUN_THETA_MAX acos(μs_min), TEXEL_MU_SKY
/// [mapping][z][y − SCATTERING_MU/2], TEXEL_VALUE_COUNT in all.
layout(std430, binding = TEXEL_COORDINATES_BINDING) buffer TexelCoordinates { real texel_values[]; };

real distance_mapping_mu_s(real mu_s) {
  PRECISE real d_min = RT - RB, d_max = horizon_distance_at_top();
  PRECISE real a = (distance_to_top(RB, mu_s) - d_min) / (d_max - d_min);
  PRECISE real A = (distance_to_top(RB, min_sun_cosine()) - d_min) / (d_max - d_min);
  return max(real(1) - a / A, real(0)) / (real(1) + a);
}

/// `theta_max` = acos(μs_min) (sun_theta_max(): computed once, the value the CPU computes per call).
real unit_from_mu_s(real mu_s, int mapping, real theta_max) {
  if (mapping == ANGLE_MAPPING_DISTANCE) return distance_mapping_mu_s(mu_s);
  PRECISE real theta = acos_r(clamp(mu_s, real(-1), real(1)));
  PRECISE real uniform_part = max(real(0), real(1) - theta / theta_max);
  return real(0.5) * distance_mapping_mu_s(mu_s) + real(0.5) * uniform_part;
}

/// Inverse of unit_from_mu_s by bisection on μs ∈ [μs_min, 1] (as on the CPU, 64 steps).
real mu_s_from_unit(real x, int mapping) {
  real lo = min_sun_cosine(), hi = real(1);
  if (x <= real(0)) return lo;
  if (x >= real(1)) return real(1);
  const real theta_max = acos_r(min_sun_cosine());
  for (int i = 0; i < 64; ++i) {
    PRECISE real mid = real(0.5) * (lo + hi);
    if (unit_from_mu_s(mid, mapping, theta_max) < x) lo = mid;
    else hi = mid;
  }
  return real(0.5) * (lo + hi);
}

/// √((1 − μ²)(1 − μs²)), the half-width of the range of ν at μ, μs (nu_spread).
real nu_spread(real mu, real mu_s) {
  PRECISE real s = sqrt(max(real(0), (real(1) - mu * mu) * (real(1) - mu_s * mu_s)));
  return s;
}

/// u_ν = φ/π, φ the azimuth between view and sun at μ, μs (scattering_u_nu).
real scattering_u_nu(real mu, real mu_s, real nu) {
  const real spread = nu_spread(mu, mu_s);
  if (!(spread > real(NU_SPREAD_MIN))) return real(0);
  PRECISE real cos_phi = clamp((nu - mu * mu_s) / spread, real(-1), real(1));
  return acos_r(cos_phi) / PI;
}

/// ν at u_ν = x for μ, μs (scattering_nu_from_unit).
real scattering_nu_from_unit(real mu, real mu_s, real x) {
  PRECISE real nu = mu * mu_s + nu_spread(mu, mu_s) * cos_r(PI * x);
  return clamp(nu, real(-1), real(1));
}

/// μ ↔ [0, 1] for rays that do not hit the ground (unit_from_mu_sky).
real unit_from_mu_sky(real r, real mu, int mapping) {
  PRECISE real H = horizon_distance_at_top(), rho = horizon_distance(r);
  PRECISE real r_mu = r * mu;
  PRECISE real d = -r_mu + safe_sqrt(r_mu * r_mu - difference_of_squares(r, RT));
  PRECISE real d_min = RT - r, d_max = rho + H;
  PRECISE real distance = d_max == d_min ? real(0) : clamp((d - d_min) / (d_max - d_min), real(0), real(1));
  if (mapping == ANGLE_MAPPING_DISTANCE) return distance;
  PRECISE real theta_horizon = acos_r(clamp(-rho / r, real(-1), real(1)));  // zenith angle of the horizon
  PRECISE real angle = clamp(acos_r(clamp(mu, real(-1), real(1))) / theta_horizon, real(0), real(1));
  PRECISE real x = real(0.5) * distance + real(0.5) * angle;
  return x;
}

/// Inverse of unit_from_mu_sky: closed form for the distance mapping, bisection for the blend.
real mu_sky_from_unit(real r, real x, int mapping) {
  PRECISE real H = horizon_distance_at_top(), rho = horizon_distance(r);
  if (mapping == ANGLE_MAPPING_DISTANCE) {
    PRECISE real d_min = RT - r, d_max = rho + H;
    PRECISE real d = d_min + (d_max - d_min) * x;
    PRECISE real mu = d == real(0) ? real(1) : clamp_cosine((H * H - rho * rho - d * d) / (real(2) * r * d));
    return mu;
  }
  real lo = -rho / r, hi = real(1);  // x decreases as μ increases
  for (int i = 0; i < 64; ++i) {
    PRECISE real mid = real(0.5) * (lo + hi);
    if (unit_from_mu_sky(r, mid, mapping) > x) lo = mid;
    else hi = mid;
  }
  return real(0.5) * (lo + hi);
}

/// r and ρ at the centre of r layer z of the scattering tables.
real texel_r(int z, out real rho_out) {
  PRECISE real u_r = (real(z) + real(0.5)) / real(SCATTERING_R);
  PRECISE real rho = horizon_distance_at_top() * unit_from_texture_coord(u_r, SCATTERING_R);
  PRECISE real r = radius_from_horizon_distance(rho);
  rho_out = rho;
  return r;
}

/// The unit coordinate of sky μ index y (≥ SCATTERING_MU/2).
real texel_unit_mu_sky(int y) {
  PRECISE real u_mu = (real(y) + real(0.5)) / real(SCATTERING_MU);
  PRECISE real x = unit_from_texture_coord(real(2) * u_mu - real(1), SCATTERING_MU / 2);
  return x;
}

struct ScatteringUV {
  real u_nu, u_mu_s, u_mu, u_r;
};

/// acos(μs_min), stored by texel_coordinates.comp.
real sun_theta_max() { return texel_values[TEXEL_SUN_THETA_MAX]; }

// The four coordinates of scattering_uvwz (parameterization.cpp) separately, so a
// loop in which some are fixed computes those once.
real scattering_u_r(real r) {
  PRECISE real H = horizon_distance_at_top();
  PRECISE real rho = horizon_distance(r);
  PRECISE real u = texture_coord_from_unit(clamp(rho / H, real(0), real(1)), SCATTERING_R);
  return u;
}

real scattering_u_mu(real r, real mu, bool hits_ground, int mapping) {
  const int half_mu = SCATTERING_MU / 2;
  if (hits_ground) {
    // Distance to the ground, between r − rb (straight down) and ρ (tangent).
    PRECISE real rho = horizon_distance(r);
    PRECISE real r_mu = r * mu;
    PRECISE real disc = r_mu * r_mu - difference_of_squares(r, RB);
    PRECISE real d = -r_mu - safe_sqrt(disc);
    PRECISE real d_min = r - RB, d_max = rho;
    PRECISE real x = d_max == d_min ? real(0) : clamp((d - d_min) / (d_max - d_min), real(0), real(1));
    PRECISE real u = real(0.5) - real(0.5) * texture_coord_from_unit(x, half_mu);
    return u;
  }
  PRECISE real u = real(0.5) + real(0.5) * texture_coord_from_unit(unit_from_mu_sky(r, mu, mapping), half_mu);
  return u;
}

real scattering_u_mu_s(real mu_s, int mapping) {
  return texture_coord_from_unit(unit_from_mu_s(mu_s, mapping, sun_theta_max()), SCATTERING_MU_S);
}

ScatteringUV scattering_uvwz(real r, real mu, real mu_s, real nu, bool hits_ground, int mapping) {
  ScatteringUV uv;
  uv.u_r = scattering_u_r(r);
  uv.u_mu = scattering_u_mu(r, mu, hits_ground, mapping);
  uv.u_mu_s = scattering_u_mu_s(mu_s, mapping);
  uv.u_nu = scattering_u_nu(mu, mu_s, nu);
  return uv;
}

struct ScatteringCoordinates {
  real r, mu, mu_s, nu;
  bool hits_ground;
};

/// Physical coordinates at the centre of texel (x, y, z) of the packed 3D table
/// (μs and sky μ from the values texel_coordinates.comp computed by bisection).
ScatteringCoordinates scattering_texel_coordinates(int x, int y, int z, int mapping) {
  const int nu_index = x / SCATTERING_MU_S, mu_s_index = x % SCATTERING_MU_S;
  PRECISE real u_mu = (real(y) + real(0.5)) / real(SCATTERING_MU);
  PRECISE real x_nu = real(nu_index) / real(SCATTERING_NU - 1);

  ScatteringCoordinates c;
  real rho;
  c.r = texel_r(z, rho);
  const int half_mu = SCATTERING_MU / 2;
  if (u_mu < real(0.5)) {
    PRECISE real d_min = c.r - RB, d_max = rho;
    PRECISE real d = d_min + (d_max - d_min) * unit_from_texture_coord(real(1) - real(2) * u_mu, half_mu);
    PRECISE real mu = d == real(0) ? real(-1) : clamp_cosine(-(rho * rho + d * d) / (real(2) * c.r * d));
    c.mu = mu;
    c.hits_ground = true;
  } else {
    c.mu = texel_values[TEXEL_MU_SKY + (mapping * SCATTERING_R + z) * half_mu + (y - half_mu)];
    c.hits_ground = false;
  }
  c.mu_s = texel_values[TEXEL_MU_S + mapping * SCATTERING_MU_S + mu_s_index];
  c.nu = scattering_nu_from_unit(c.mu, c.mu_s, x_nu);
  return c;
}

// ------------------------------------------------------------ tables (table.cpp)
// GL_LINEAR + GL_CLAMP_TO_EDGE by hand from texelFetch, weights in `real`, so the
// result is the CPU's Table2D/Table3D::sample (hardware filtering has 8-bit weights on some GPUs).

struct Lerp {
  int i0, i1;
  real t;
};

Lerp linear_taps(real u, int n) {
  PRECISE real x = u * real(n) - real(0.5);
  PRECISE real f = floor(x);
  Lerp l;
  l.t = x - f;
  const int i = int(f);
  l.i0 = clamp(i, 0, n - 1);
  l.i1 = clamp(i + 1, 0, n - 1);
  return l;
}

real4 sample_table_2d(sampler2D table, int width, int height, real u, real v) {
  const Lerp a = linear_taps(u, width), b = linear_taps(v, height);
  const real4 p00 = real4(texelFetch(table, ivec2(a.i0, b.i0), 0)), p10 = real4(texelFetch(table, ivec2(a.i1, b.i0), 0)),
              p01 = real4(texelFetch(table, ivec2(a.i0, b.i1), 0)), p11 = real4(texelFetch(table, ivec2(a.i1, b.i1), 0));
  PRECISE real w00 = (real(1) - a.t) * (real(1) - b.t), w10 = a.t * (real(1) - b.t), w01 = (real(1) - a.t) * b.t,
             w11 = a.t * b.t;
  return w00 * p00 + w10 * p10 + w01 * p01 + w11 * p11;
}

real4 sample_table_3d(sampler3D table, int width, int height, int depth, real u, real v, real w) {
  const Lerp a = linear_taps(u, width), b = linear_taps(v, height), d = linear_taps(w, depth);
  real4 out_value = real4(0);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        PRECISE real weight = (i == 0 ? real(1) - a.t : a.t) * (j == 0 ? real(1) - b.t : b.t) *
                            (k == 0 ? real(1) - d.t : d.t);
        if (weight == real(0)) continue;
        const ivec3 p = ivec3(i == 0 ? a.i0 : a.i1, j == 0 ? b.i0 : b.i1, k == 0 ? d.i0 : d.i1);
        out_value += weight * real4(texelFetch(table, p, 0));
      }
  return out_value;
}

/// sample_scattering_table (lookup_tables.cpp): trilinear in (μs, μ, r) within the
/// two nearest ν slices, then linear in ν by hand.
real4 sample_scattering_table(sampler3D table, ScatteringUV uv) {
  PRECISE real x_nu = uv.u_nu * real(SCATTERING_NU - 1);
  PRECISE real nu_floor = min(floor(x_nu), real(SCATTERING_NU - 1));
  PRECISE real t = x_nu - nu_floor;
  PRECISE real u0 = (nu_floor + uv.u_mu_s) / real(SCATTERING_NU);
  PRECISE real u1 = (min(nu_floor + real(1), real(SCATTERING_NU - 1)) + uv.u_mu_s) / real(SCATTERING_NU);
  const int width = SCATTERING_NU * SCATTERING_MU_S;
  const real4 a = sample_table_3d(table, width, SCATTERING_MU, SCATTERING_R, u0, uv.u_mu, uv.u_r);
  const real4 b = sample_table_3d(table, width, SCATTERING_MU, SCATTERING_R, u1, uv.u_mu, uv.u_r);
  return a * (real(1) - t) + b * t;
}

/// geometric_blend (lookup_tables.h): a^(1−t)·b^t while |ln(b/a)| ≤
/// GEOMETRIC_BLEND_FULL_LOG_RATIO (kGeometricBlendFullLogRatio, defined by the
/// shader model), fading to linear over the next unit, linear where either is
/// zero; logarithm and exponential in float, as on the CPU.
real geometric_blend(real a, real b, real t) {
  const real linear_value = a * (real(1) - t) + b * t;
  if (!(a > real(0) && b > real(0))) return linear_value;
  const float log_ratio = log(float(clamp(b / a, real(1e-30), real(1e30))));
  const float weight = clamp(GEOMETRIC_BLEND_FULL_LOG_RATIO + 1.0 - abs(log_ratio), 0.0, 1.0);
  if (weight == 0.0) return linear_value;
  const real geometric = a * real(exp(float(t) * log_ratio));
  return linear_value + real(weight) * (geometric - linear_value);
}
real4 geometric_blend(real4 a, real4 b, real t) {
  return real4(geometric_blend(a.x, b.x, t), geometric_blend(a.y, b.y, t), geometric_blend(a.z, b.z, t),
               geometric_blend(a.w, b.w, t));
}

/// The μs texel columns either side of u_μs and the blend weight between them
/// (sample_scattering_table_geometric_mu_s, lookup_tables.cpp).
struct MuSColumns {
  real u_a, u_b, t;
};
MuSColumns mu_s_columns(real u_mu_s) {
  const real n = real(SCATTERING_MU_S);
  PRECISE real x = clamp(u_mu_s * n - real(0.5), real(0), n - real(1));
  PRECISE real i0 = min(floor(x), n - real(2));
  MuSColumns c;
  c.t = x - i0;
  c.u_a = (i0 + real(0.5)) / n;
  c.u_b = (i0 + real(1.5)) / n;
  return c;
}

/// sample_scattering_table_geometric_mu_s (lookup_tables.cpp): the final
/// tables' read, geometric in μs between the two nearest texel columns, each
/// read like sample_scattering_table.
real4 sample_scattering_table_geometric_mu_s(sampler3D table, ScatteringUV uv) {
  const MuSColumns c = mu_s_columns(uv.u_mu_s);
  ScatteringUV column_a = uv, column_b = uv;
  column_a.u_mu_s = c.u_a;
  column_b.u_mu_s = c.u_b;
  return geometric_blend(sample_scattering_table(table, column_a), sample_scattering_table(table, column_b), c.t);
}

// ------------------------------------------------------------ transmittance queries (lookup_tables.cpp)

layout(binding = TRANSMITTANCE_UNIT) uniform sampler2D transmittance_texture;

real4 transmittance_to_top(real r, real mu) {
  const real2 uv = transmittance_uv(r, mu);
  return sample_table_2d(transmittance_texture, TRANSMITTANCE_MU, TRANSMITTANCE_R, uv.x, uv.y);
}

real transmittance_ratio(real a, real b) { return b > real(0) ? min(a / b, real(1)) : real(0); }
real4 transmittance_ratio(real4 a, real4 b) {
  return real4(transmittance_ratio(a.x, b.x), transmittance_ratio(a.y, b.y), transmittance_ratio(a.z, b.z),
               transmittance_ratio(a.w, b.w));
}

/// TableQueries::transmittance: T over a distance d along (r, μ), always from ratios of
/// transmittances to the top along upward rays (three cases, as on the CPU).
real4 transmittance(real r, real mu, real d, bool hits_ground) {
  PRECISE real r_d = clamp(sqrt(d * d + real(2) * r * mu * d + r * r), RB, RT);
  PRECISE real mu_d = clamp((r * mu + d) / r_d, real(-1), real(1));
  if (mu >= real(0) && !hits_ground) {
    return transmittance_ratio(transmittance_to_top(r, mu), transmittance_to_top(r_d, mu_d));
  } else if (hits_ground || mu_d <= real(0)) {
    return transmittance_ratio(transmittance_to_top(r_d, -mu_d), transmittance_to_top(r, -mu));
  }
  PRECISE real r_p = max(r * sqrt(max(real(0), real(1) - mu * mu)), RB);
  const real4 p = transmittance_to_top(r_p, real(0));
  const real4 a = transmittance_to_top(r, -mu);
  const real4 b = transmittance_to_top(r_d, mu_d);
  // Per lane, 0 where a or b is not positive; selected on whole vectors (NVIDIA refuses a double
  // vector written at a non-constant index, C9999 __setVectorIndex).
  const bvec4 positive = bvec4(uvec4(greaterThan(a, real4(0))) & uvec4(greaterThan(b, real4(0))));
  const real4 safe_a = mix(real4(1), a, positive), safe_b = mix(real4(1), b, positive);
  return mix(real4(0), min(p / safe_a, real4(1)) * min(p / safe_b, real4(1)), positive);
}

/// TableQueries::transmittance_to_sun: zero when the planet blocks the sun's centre.
real4 transmittance_to_sun(real r, real mu_s) {
  if (ray_hits_ground(r, mu_s)) return real4(0);
  return transmittance_to_top(r, mu_s);
}

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

/// The slab of r (z) layers one dispatch covers starts here.
uniform int z_offset;
