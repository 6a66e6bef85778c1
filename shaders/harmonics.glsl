// Spherical harmonics of the scattering density (atmosphere/lut/spherical_harmonics.h,
// cpu_precompute.cpp: compute_scattering_density_harmonics), shared by
// radiance_harmonics.comp, harmonic_projection.comp and harmonic_density.comp.
// Needs atmosphere_common.glsl.
//
// A column is one (r, μs) pair of the scattering table: column = z · SCATTERING_MU_S + μs index.
// Defines (render/lut/shader_model.cpp):
//   HARMONIC_DEGREE    L, the highest degree (≤ 2 · SPHERE_ZENITH_SAMPLES − 1)
//   HARMONIC_RULE      TableData offset of the horizon-split rules: per r layer
//                      2·SPHERE_ZENITH_SAMPLES μ nodes (ground part first), then as many weights
//   RAYLEIGH_MOMENTS   TableData offset of the Rayleigh phase's Legendre moments p_0..p_L
//   MIE_MOMENTS        TableData offset of the Mie phase's, L + 1 per wavelength

const int HARMONIC_NODES = 2 * SPHERE_ZENITH_SAMPLES;  // μ nodes per column
const int HALF_AZIMUTHS = 2 * SPHERE_ZENITH_SAMPLES;   // azimuths over [0, π), mirrored over (π, 2π)
const int HARMONIC_ORDERS = HARMONIC_DEGREE + 1;      // m = 0..L
const int HARMONIC_COUNT = (HARMONIC_DEGREE + 1) * (HARMONIC_DEGREE + 2) / 2;
const int COLUMNS = SCATTERING_R * SCATTERING_MU_S;

/// C_m(μ_j) = ∫ L(μ_j, φ) cos(mφ) dφ per column, node and m (radiance_harmonics.comp).
layout(std430, binding = AZIMUTH_MOMENTS_BINDING) buffer AzimuthMoments { real4 azimuth_moments[]; };
/// a_lm per column, m-major (harmonic_projection.comp).
layout(std430, binding = HARMONIC_COEFFICIENTS_BINDING) buffer HarmonicCoefficients { real4 harmonic_coefficients[]; };

int azimuth_moment_index(int column, int node, int m) { return (column * HARMONIC_NODES + node) * HARMONIC_ORDERS + m; }

/// harmonic_index of spherical_harmonics.h: (l, m) in the m-major packing.
int harmonic_index(int l, int m) { return m * (HARMONIC_DEGREE + 1) - m * (m - 1) / 2 + (l - m); }

real harmonic_rule_mu(int z, int node) { return table_data[HARMONIC_RULE + z * 2 * HARMONIC_NODES + node]; }
real harmonic_rule_weight(int z, int node) {
  return table_data[HARMONIC_RULE + z * 2 * HARMONIC_NODES + HARMONIC_NODES + node];
}

/// c_m of the cos(mφ) harmonics: 1 for m = 0, √2 otherwise.
real azimuth_normalisation(int m) { return m == 0 ? real(1) : sqrt(real(2)); }

/// P̄_m^m(x) (normalized_legendre in spherical_harmonics.cpp, the same products in the same order).
real legendre_diagonal(int m, real x) {
  const real s = sqrt(max(real(0), real(1) - x * x));
  real p = real(1) / sqrt(real(4) * PI);
  for (int k = 1; k <= m; ++k) p *= sqrt((real(2) * real(k) + real(1)) / (real(2) * real(k))) * s;
  return p;
}

/// P̄_l^m from P̄_{l−1}^m (p1) and P̄_{l−2}^m (p2), l ≥ m + 2.
real legendre_step(int l, int m, real x, real p1, real p2) {
  const real ll = real(l), mm = real(m);
  const real a = sqrt((real(4) * ll * ll - real(1)) / ((ll - mm) * (ll + mm)));
  const real b = sqrt((real(2) * ll + real(1)) * (ll + mm - real(1)) * (ll - mm - real(1)) /
                      ((ll - mm) * (ll + mm) * (real(2) * ll - real(3))));
  return a * x * p1 - b * p2;
}
