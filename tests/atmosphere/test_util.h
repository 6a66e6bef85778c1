#pragma once
// Small numerical helpers shared by the atmosphere tests: integration over the
// sphere, tables of published values.
#include <cmath>
#include <functional>
#include <initializer_list>

#include <gtest/gtest.h>

#include "atmosphere/constants.h"

namespace zenith::atmosphere::test {

/// ∫_{4π} P(cos θ) dω = 2π ∫_{-1}^{1} P(μ) dμ by composite Gauss–Legendre
/// quadrature (4 nodes per panel); `panels` high enough for sharp HG lobes.
inline double integrate_over_sphere(const std::function<double(double)>& phase, int panels = 4000) {
  static constexpr double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static constexpr double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double a = -1.0 + 2.0 * p / panels, b = -1.0 + 2.0 * (p + 1) / panels;
    for (int k = 0; k < 4; ++k) sum += w[k] * 0.5 * (b - a) * phase(0.5 * (a + b) + 0.5 * (b - a) * x[k]);
  }
  return 2.0 * kPi * sum;
}

/// The same integral with u = sin(θ/2) as the variable, cos θ = 1 − 2u²:
///   ∫_{4π} f dω = 8π ∫_0^1 f(1 − 2u²) u du,
/// on `panels` equal panels of u. With panels a multiple of 255 every panel
/// lies inside one segment of TabulatedPhase's grid, where its interpolant and
/// its proposal are smooth: the rule is exact to rounding for them.
inline double integrate_over_sphere_in_sin_half_angle(const std::function<double(double)>& f, int panels = 255 * 8) {
  static constexpr double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static constexpr double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double a = double(p) / panels, b = double(p + 1) / panels;
    for (int k = 0; k < 4; ++k) {
      const double u = 0.5 * (a + b) + 0.5 * (b - a) * x[k];
      sum += w[k] * 0.5 * (b - a) * f(1.0 - 2.0 * u * u) * u;
    }
  }
  return 8.0 * kPi * sum;
}

/// A published value of a function of one variable: f(x) = expected within tolerance.
struct PublishedValue {
  double x, expected, tolerance;
};

/// Expects `f` to reproduce every one of `values` (a table of a paper or a standard).
inline void expect_published_values(const std::function<double(double)>& f,
                                    std::initializer_list<PublishedValue> values) {
  for (const PublishedValue& v : values) EXPECT_NEAR(f(v.x), v.expected, v.tolerance) << "at " << v.x;
}

}  // namespace zenith::atmosphere::test
