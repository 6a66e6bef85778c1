#version 450 core
// Scattering density, step 2 of 3 (harmonics.glsl): for one column (r, μs)
// and one m, the harmonic coefficients a_lm = Σ_j w_j c_m P̄_l^m(μ_j) C_m(μ_j),
// l = m..L, over the nodes of the column's horizon-split rule. One group of 4 wavelengths.
layout(local_size_x = 64) in;

#include "atmosphere_common.glsl"
#include "harmonics.glsl"

void main() {
  const int invocation = int(gl_GlobalInvocationID.x);
  if (invocation >= COLUMNS * HARMONIC_ORDERS) return;
  const int column = invocation / HARMONIC_ORDERS, m = invocation % HARMONIC_ORDERS;
  const int z = column / SCATTERING_MU_S;
  // P̄_{l−1}^m and P̄_{l−2}^m at every node, advanced one l at a time.
  real p1[HARMONIC_NODES], p2[HARMONIC_NODES];
  for (int j = 0; j < HARMONIC_NODES; ++j) {
    p1[j] = legendre_diagonal(m, harmonic_rule_mu(z, j));
    p2[j] = real(0);
  }
  const real cm = azimuth_normalisation(m);
  for (int l = m; l <= HARMONIC_DEGREE; ++l) {
    real4 a = real4(0);
    for (int j = 0; j < HARMONIC_NODES; ++j) {
      const real x = harmonic_rule_mu(z, j);
      real p = p1[j];
      if (l == m + 1) {
        p = sqrt(real(2) * real(m) + real(3)) * x * p1[j];
      } else if (l >= m + 2) {
        p = legendre_step(l, m, x, p1[j], p2[j]);
      }
      if (l > m) {
        p2[j] = p1[j];
        p1[j] = p;
      }
      a += (cm * harmonic_rule_weight(z, j)) * p * azimuth_moments[azimuth_moment_index(column, j, m)];
    }
    harmonic_coefficients[column * HARMONIC_COUNT + harmonic_index(l, m)] = a;
  }
}
