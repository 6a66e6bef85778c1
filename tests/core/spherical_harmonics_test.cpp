// The real spherical harmonics of degree 3 and 4 against their closed forms:
// the addition theorem, which the Moon's shadow relies on (astro/moon_shadow.h),
// and orthonormality over the sphere.
#include "core/spherical_harmonics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/units.h"

namespace zenith::core {
namespace {

double legendre_3(double x) { return 0.5 * x * (5.0 * x * x - 3.0); }
double legendre_4(double x) { return (35.0 * x * x * x * x - 30.0 * x * x + 3.0) / 8.0; }

TEST(SphericalHarmonics, SumOverEachDegreeIsItsLegendrePolynomial) {
  // Σ_m Y_lm(u) Y_lm(v) = (2l + 1)/(4π) P_l(u·v) for unit u, v.
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const auto unit = [&] {
    double x = normal(rng), y = normal(rng), z = normal(rng);
    const double r = std::sqrt(x * x + y * y + z * z);
    return std::array<double, 3>{x / r, y / r, z / r};
  };
  for (int trial = 0; trial < 200; ++trial) {
    const auto u = unit(), v = unit();
    const auto a = spherical_harmonics_3_4(u[0], u[1], u[2]), b = spherical_harmonics_3_4(v[0], v[1], v[2]);
    double l3 = 0.0, l4 = 0.0;
    for (int n = 0; n < 7; ++n) l3 += a[n] * b[n];
    for (int n = 7; n < 16; ++n) l4 += a[n] * b[n];
    const double cosine = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    EXPECT_NEAR(l3, 7.0 / (4.0 * kPi) * legendre_3(cosine), 1e-12);
    EXPECT_NEAR(l4, 9.0 / (4.0 * kPi) * legendre_4(cosine), 1e-12);
  }
}

TEST(SphericalHarmonics, AreOrthonormalOverTheSphere) {
  // ∫ Y_i Y_j dω by Gauss–Legendre in cos θ (16 nodes, exact for these degree-8 products) and 32 azimuths
  // (exact for |m| + |m'| < 32).
  const double nodes[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                           0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
  const double weights[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                             0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};
  double gram[16][16] = {};
  for (int k = 0; k < 16; ++k) {
    const double z = (k < 8 ? -1.0 : 1.0) * nodes[k % 8], w_z = weights[k % 8], rho = std::sqrt(1.0 - z * z);
    for (int j = 0; j < 32; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / 32.0, w = w_z * 2.0 * kPi / 32.0;
      const auto y = spherical_harmonics_3_4(rho * std::cos(phi), rho * std::sin(phi), z);
      for (int a = 0; a < 16; ++a)
        for (int b = 0; b < 16; ++b) gram[a][b] += w * y[a] * y[b];
    }
  }
  for (int a = 0; a < 16; ++a)
    for (int b = 0; b < 16; ++b) EXPECT_NEAR(gram[a][b], a == b ? 1.0 : 0.0, 1e-12) << a << ", " << b;
}

}  // namespace
}  // namespace zenith::core
