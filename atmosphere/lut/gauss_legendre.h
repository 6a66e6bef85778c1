#pragma once
// Gauss–Legendre quadrature nodes and weights on [−1, 1], for the direction
// integrals of the precomputation. Quadrature in μ = cos θ (rather than the
// midpoint rule in θ) integrates ∫ sin θ dθ and ∫ cos θ sin θ dθ exactly, so a
// conservative atmosphere over a white ground neither gains nor loses light to
// the quadrature: with 4 zenith steps the θ-midpoint rule overestimates the
// irradiance of an isotropic sky by 2.6% per scattering order.
#include <cmath>
#include <vector>

#include "atmosphere/constants.h"

namespace zenith::atmosphere::lut {

struct GaussLegendre {
  std::vector<double> nodes, weights;  ///< Σ weights = 2

  /// n-point rule by Newton iteration on the Legendre polynomial P_n.
  explicit GaussLegendre(int n) {
    nodes.resize(std::size_t(n));
    weights.resize(std::size_t(n));
    for (int i = 0; i < n; ++i) {
      double x = std::cos(kPi * (i + 0.75) / (n + 0.5));  // initial guess
      double dp = 1.0;
      for (int iteration = 0; iteration < 100; ++iteration) {
        double p0 = 1.0, p1 = x;  // P_0, P_1
        for (int k = 2; k <= n; ++k) {
          const double pk = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = pk;
        }
        dp = n * (x * p1 - p0) / (x * x - 1.0);  // P_n'(x)
        const double dx = p1 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-15) break;
      }
      nodes[std::size_t(i)] = x;
      weights[std::size_t(i)] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
  }
};

}  // namespace zenith::atmosphere::lut
