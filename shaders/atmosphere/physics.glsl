// The model's physics on the GPU (included by atmosphere_common.glsl, after
// maths.glsl): the model's data (WavelengthData, TableData), the density
// profiles, extinction, the air-mass stretch and the phase functions, each the
// twin of its C++ function in atmosphere/.

// ------------------------------------------------------------ model data

/// A header of MODEL_HEADER_VECTORS real4s — (bottom radius, top radius,
/// Rayleigh depolarisation δ, H), (Rayleigh phase model, Mie phase model,
/// WAVELENGTH_FIELDS, has Mie), (the μs mapping's limit, MIE_TABLE, 0, 0) — which the render passes' shared programs
/// (MODEL_AT_RUN_TIME 1) read where the precompute's have defines; then per
/// wavelength group g, WAVELENGTH_FIELDS real4s
/// (the FIELD_* indices, defined by the shader model), one lane per wavelength:
/// the model's parameters (scattering and extinction coefficients, the Mie
/// phase's g1, g2 and α, the ground albedo, the absorbers). This block is the one
/// way they reach a shader, the precompute's and the render passes' alike
/// (render/lut/shader_model.h: ModelBuffers). A uniform block (std140, whose
/// real4 array has the std430 stride, WAVELENGTH_DATA_SIZE = header + groups ×
/// fields in the precompute, the largest block in the shared programs):
/// a CPU rasterizer reads it once per SIMD vector, where it would read a storage
/// buffer lane by lane inside branches.
layout(std140, binding = WAVELENGTH_DATA_BINDING) uniform WavelengthData { real4 wavelength_data[WAVELENGTH_DATA_SIZE]; };
/// Profile descriptors (kind, scale height, first knot, knot count), spline
/// knots (x[], y[], slope[]), the direction quadratures (nodes[], weights[]) and
/// the air-mass table (cos zenith[], stretch[]).
layout(std430, binding = TABLE_DATA_BINDING) readonly buffer TableData { real table_data[]; };

uniform int wavelength_group;
#define WAVELENGTH_GROUP_DECLARED 1  // render/frame.glsl reads the same uniform

real4 wavelength_field(int field) {
  return wavelength_data[MODEL_HEADER_VECTORS + wavelength_group * WAVELENGTH_FIELDS + field];
}

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

#if !MODEL_AT_RUN_TIME  // the precompute's alone: the render passes read them from the tables
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
#endif  // !MODEL_AT_RUN_TIME

// ------------------------------------------------------------ phase functions (phase_functions.cpp)

/// The three Rayleigh phases (RayleighPhaseModel): 0 classic 3/4 (1 + c²),
/// 1 Penndorf A (1 + B c²), 2 depolarised with γ = δ/(2 − δ); each / 4π.
/// RAYLEIGH_PHASE picks one, or in the shared render programs WavelengthData's
/// header, a branch every invocation takes alike.
real rayleigh_phase_classic(real c) { return real(0.75) * (real(1) + c * c) * INV_4PI; }
real rayleigh_phase_penndorf(real c) { return PENNDORF_A * (real(1) + PENNDORF_B * c * c) * INV_4PI; }
real rayleigh_phase_depolarized(real c) {
  const real delta = RAYLEIGH_DEPOLARIZATION;
  const real gamma = delta / (real(2) - delta);
  return real(3) / (real(4) * (real(1) + real(2) * gamma)) * ((real(1) + real(3) * gamma) + (real(1) - gamma) * c * c) *
         INV_4PI;
}

real rayleigh_phase(real c) {
#if MODEL_AT_RUN_TIME
  const int model = int(wavelength_data[1].x);
  if (model == 0) return rayleigh_phase_classic(c);
  if (model == 1) return rayleigh_phase_penndorf(c);
  return rayleigh_phase_depolarized(c);
#elif RAYLEIGH_PHASE == 0
  return rayleigh_phase_classic(c);
#elif RAYLEIGH_PHASE == 1
  return rayleigh_phase_penndorf(c);
#else
  return rayleigh_phase_depolarized(c);
#endif
}

#if HAS_MIE
real4 henyey_greenstein(real c, real4 g) {
  const real4 denom = real(1) + g * g - real(2) * g * c;
  return (real(1) - g * g) / (denom * sqrt(denom)) * INV_4PI;
}

real4 cornette_shanks(real c, real4 g) {
  const real4 denom = real(1) + g * g - real(2) * g * c;
  return real(3) * (real(1) - g * g) * (real(1) + c * c) / (real(2) * (real(2) + g * g) * denom * sqrt(denom)) *
         INV_4PI;
}

/// MiePhase (atmosphere/phase_functions.cpp): P_M(cos θ) for 4 wavelengths with
/// their asymmetry parameters g1 and, for the double Henyey–Greenstein, the
/// second lobe's g2 and the first lobe's weight α (the only function that reads
/// them; MIE_PHASE picks the model, or in the shared render programs
/// WavelengthData's header, a branch every invocation takes alike):
///   0 Henyey–Greenstein   P = HG(c, g1),  HG(c, g) = (1 − g²) / (1 + g² − 2 g c)^{3/2} / 4π
///   1 double HG           P = α HG(c, g1) + (1 − α) HG(c, g2)
///   2 Cornette–Shanks     P = 3 (1 − g1²)(1 + c²) / (2 (2 + g1²)(1 + g1² − 2 g1 c)^{3/2}) / 4π
///   3 tabulated           P linear in u = sin(θ/2) between MIE_TABLE_SAMPLES samples
/// The precompute and the render passes call it through model_mie_phase.
real4 tabulated_mie_phase(real c);
real4 mie_phase(real c, real4 g1, real4 g2, real4 alpha) {
#if MODEL_AT_RUN_TIME
  const int model = int(wavelength_data[1].y);
  if (model == 0) return henyey_greenstein(c, g1);
  if (model == 1) return alpha * henyey_greenstein(c, g1) + (real(1) - alpha) * henyey_greenstein(c, g2);
  if (model == 3) return tabulated_mie_phase(c);
  return cornette_shanks(c, g1);
#elif MIE_PHASE == 0
  return henyey_greenstein(c, g1);
#elif MIE_PHASE == 1
  return alpha * henyey_greenstein(c, g1) + (real(1) - alpha) * henyey_greenstein(c, g2);
#elif MIE_PHASE == 3
  return tabulated_mie_phase(c);
#else
  return cornette_shanks(c, g1);
#endif
}

/// One lane of tabulated_mie_phase: the samples at `at` and `at` + 1, f of the way.
real tabulated_mie_sample(int at, real f) { return table_data[at] + f * (table_data[at + 1] - table_data[at]); }

/// TabulatedPhase::operator() (atmosphere/tabulated_phase.cpp) for the
/// wavelength group's 4 lanes: MIE_TABLE_SAMPLES samples per wavelength in
/// TableData from MIE_TABLE, on a grid uniform in u = √((1 − c)/2), P linear
/// in u between them. The lanes are read one by one, no loop: NVIDIA refuses a
/// double vector written at a variable index, and a buffer index that follows
/// a loop's counter inside the callers' loops (tests/render/glsl_nvidia_rules_test.cpp).
real4 tabulated_mie_phase(real c) {
  PRECISE real u = sqrt(max(real(0), real(0.5) - real(0.5) * c));
  PRECISE real x = min(u, real(1)) * real(MIE_TABLE_SAMPLES - 1);
  const int k = min(int(x), MIE_TABLE_SAMPLES - 2);
  const real f = x - real(k);
  const int at = MIE_TABLE + wavelength_group * 4 * MIE_TABLE_SAMPLES + k;
  return real4(tabulated_mie_sample(at, f), tabulated_mie_sample(at + MIE_TABLE_SAMPLES, f),
               tabulated_mie_sample(at + 2 * MIE_TABLE_SAMPLES, f), tabulated_mie_sample(at + 3 * MIE_TABLE_SAMPLES, f));
}

/// The model's Mie phase for the wavelength group being computed: mie_phase
/// with g1, g2 and α from WavelengthData.
real4 model_mie_phase(real c) {
  return mie_phase(c, wavelength_field(FIELD_MIE_G1), wavelength_field(FIELD_MIE_G2), wavelength_field(FIELD_MIE_ALPHA));
}
#endif
