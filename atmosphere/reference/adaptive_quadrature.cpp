#include "atmosphere/reference/adaptive_quadrature.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace zenith::atmosphere::reference {

namespace {

// 15-point Kronrod abscissae on [−1, 1] (non-negative half, descending) and weights;
// the odd-indexed abscissae 1, 3, 5 and the centre are the 7-point Gauss nodes.
constexpr double kKronrodNodes[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                                     0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                                     0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                                     0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr double kKronrodWeights[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                       0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                       0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                       0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
// Gauss weights for the nodes kKronrodNodes[1], [3], [5] and the centre [7].
constexpr double kGaussWeights[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                     0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Panel {
  double a = 0.0, b = 0.0;
  std::vector<double> integral, error;
  bool splittable = true;
};

/// K15 and |K15 − G7| on [a, b] for every component.
void gauss_kronrod_15(const VectorIntegrand& f, std::size_t n, Panel& panel, std::vector<double>& fa,
                      std::vector<double>& fb, std::vector<double>& gauss) {
  const double centre = 0.5 * (panel.a + panel.b);
  const double half = 0.5 * (panel.b - panel.a);
  panel.integral.assign(n, 0.0);
  panel.error.assign(n, 0.0);
  gauss.assign(n, 0.0);
  f(centre, fa);
  for (std::size_t i = 0; i < n; ++i) {
    panel.integral[i] = kKronrodWeights[7] * fa[i];
    gauss[i] = kGaussWeights[3] * fa[i];
  }
  for (int k = 0; k < 7; ++k) {
    const double dx = half * kKronrodNodes[k];
    f(centre - dx, fa);
    f(centre + dx, fb);
    for (std::size_t i = 0; i < n; ++i) {
      const double pair = fa[i] + fb[i];
      panel.integral[i] += kKronrodWeights[k] * pair;
      if (k % 2 == 1) gauss[i] += kGaussWeights[k / 2] * pair;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    panel.integral[i] *= half;
    gauss[i] *= half;
    panel.error[i] = std::abs(panel.integral[i] - gauss[i]);
  }
  // A panel too short to be bisected again in floating point is final.
  const double scale = std::max(std::abs(panel.a), std::abs(panel.b));
  panel.splittable = (panel.b - panel.a) > 64.0 * std::numeric_limits<double>::epsilon() * scale;
}

}  // namespace

QuadratureResult integrate_adaptive(const VectorIntegrand& f, std::span<const double> breakpoints,
                                    std::size_t components, const QuadratureOptions& options) {
  if (breakpoints.size() < 2) throw std::invalid_argument("integrate_adaptive: need at least two breakpoints");
  for (std::size_t k = 1; k < breakpoints.size(); ++k)
    if (!(breakpoints[k] >= breakpoints[k - 1]))
      throw std::invalid_argument("integrate_adaptive: breakpoints must not decrease");
  const std::size_t n = components;
  QuadratureResult result;
  result.integral.assign(n, 0.0);
  result.error_estimate.assign(n, 0.0);

  std::vector<double> fa(n), fb(n), gauss(n);
  std::vector<Panel> panels;
  for (std::size_t k = 1; k < breakpoints.size(); ++k) {
    if (!(breakpoints[k] > breakpoints[k - 1])) continue;
    Panel p;
    p.a = breakpoints[k - 1];
    p.b = breakpoints[k];
    gauss_kronrod_15(f, n, p, fa, fb, gauss);
    result.evaluations += 15;
    panels.push_back(std::move(p));
  }

  std::vector<double> total(n), error(n), tolerance(n);
  auto recompute_totals = [&] {
    std::fill(total.begin(), total.end(), 0.0);
    std::fill(error.begin(), error.end(), 0.0);
    for (const Panel& p : panels)
      for (std::size_t i = 0; i < n; ++i) {
        total[i] += p.integral[i];
        error[i] += p.error[i];
      }
    for (std::size_t i = 0; i < n; ++i)
      tolerance[i] = std::max({options.absolute_tolerance, options.relative_tolerance * std::abs(total[i]),
                               std::numeric_limits<double>::min()});
  };
  auto converged = [&] {
    for (std::size_t i = 0; i < n; ++i)
      if (error[i] > tolerance[i]) return false;
    return true;
  };
  // The panel whose worst component uses the largest share of its tolerance.
  auto worst_panel = [&]() -> std::ptrdiff_t {
    std::ptrdiff_t worst = -1;
    double worst_ratio = 0.0;
    for (std::size_t k = 0; k < panels.size(); ++k) {
      if (!panels[k].splittable) continue;
      double ratio = 0.0;
      for (std::size_t i = 0; i < n; ++i) ratio = std::max(ratio, panels[k].error[i] / tolerance[i]);
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        worst = std::ptrdiff_t(k);
      }
    }
    return worst;
  };

  recompute_totals();
  while (!converged() && panels.size() < options.max_panels) {
    const std::ptrdiff_t k = worst_panel();
    if (k < 0) break;  // nothing left that floating point can bisect
    Panel left, right;
    left.a = panels[std::size_t(k)].a;
    left.b = right.a = 0.5 * (panels[std::size_t(k)].a + panels[std::size_t(k)].b);
    right.b = panels[std::size_t(k)].b;
    gauss_kronrod_15(f, n, left, fa, fb, gauss);
    gauss_kronrod_15(f, n, right, fa, fb, gauss);
    result.evaluations += 30;
    panels[std::size_t(k)] = std::move(left);
    panels.push_back(std::move(right));
    recompute_totals();
  }

  result.integral = total;
  result.error_estimate = error;
  result.panels = panels.size();
  result.converged = converged();
  return result;
}

}  // namespace zenith::atmosphere::reference
