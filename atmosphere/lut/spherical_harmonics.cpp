#include "atmosphere/lut/spherical_harmonics.h"

#include <algorithm>
#include <cmath>

#include "atmosphere/constants.h"
#include "atmosphere/lut/gauss_legendre.h"

namespace zenith::atmosphere::lut {

double azimuth_normalisation(int m) { return m == 0 ? 1.0 : std::sqrt(2.0); }

void normalized_legendre(int degree, double x, double* out) {
  const double s = std::sqrt(std::max(0.0, 1.0 - x * x));
  double p_mm = 1.0 / std::sqrt(4.0 * kPi);  // P̄_0^0
  for (int m = 0; m <= degree; ++m) {
    if (m > 0) p_mm *= std::sqrt((2.0 * m + 1.0) / (2.0 * m)) * s;
    double* column = out + harmonic_index(degree, m, m);
    column[0] = p_mm;
    if (m == degree) break;
    column[1] = std::sqrt(2.0 * m + 3.0) * x * p_mm;
    for (int l = m + 2; l <= degree; ++l) {
      const double ll = l, mm = m;
      const double a = std::sqrt((4.0 * ll * ll - 1.0) / ((ll - mm) * (ll + mm)));
      const double b =
          std::sqrt((2.0 * ll + 1.0) * (ll + mm - 1.0) * (ll - mm - 1.0) / ((ll - mm) * (ll + mm) * (2.0 * ll - 3.0)));
      column[l - m] = a * x * column[l - m - 1] - b * column[l - m - 2];
    }
  }
}

std::vector<double> phase_legendre_moments(const std::function<double(double)>& phase, int degree) {
  static const GaussLegendre rule(1024);  // immutable after construction (thread-safe static)
  std::vector<double> moments(static_cast<std::size_t>(degree) + 1, 0.0);
  for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
    const double x = rule.nodes[i];
    const double w = 2.0 * kPi * rule.weights[i] * phase(x);
    double p0 = 1.0, p1 = x;  // P_0, P_1 (Bonnet's recurrence)
    for (int l = 0; l <= degree; ++l) {
      double p = l == 0 ? p0 : p1;
      if (l >= 2) {
        p = ((2.0 * l - 1.0) * x * p1 - (l - 1.0) * p0) / l;
        p0 = p1;
        p1 = p;
      }
      moments[static_cast<std::size_t>(l)] += w * p;
    }
  }
  return moments;
}

HorizonSplitRule::HorizonSplitRule(double bottom_radius_m, double r_m, int nodes_per_part) {
  const GaussLegendre rule(nodes_per_part);
  const double ratio = std::min(bottom_radius_m / r_m, 1.0);
  const double mu_horizon = -std::sqrt(std::max(0.0, 1.0 - ratio * ratio));
  ground_nodes = nodes_per_part;
  auto add_part = [&](double lo, double hi) {
    const double half = 0.5 * (hi - lo), centre = 0.5 * (hi + lo);
    for (int i = nodes_per_part - 1; i >= 0; --i) {  // GaussLegendre's nodes descend
      mu.push_back(centre + half * rule.nodes[static_cast<std::size_t>(i)]);
      weight.push_back(half * rule.weights[static_cast<std::size_t>(i)]);
    }
  };
  add_part(-1.0, mu_horizon);
  add_part(mu_horizon, 1.0);
}

}  // namespace zenith::atmosphere::lut
