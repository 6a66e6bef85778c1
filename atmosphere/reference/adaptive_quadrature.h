#pragma once
// Globally adaptive Gauss–Kronrod quadrature of vector-valued integrands, the
// deterministic workhorse of the reference solver (optical depths and single
// scattering). One integrand evaluation returns every component (e.g. every
// working wavelength) at once, so all components share the abscissae.
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

namespace zenith::atmosphere::reference {

/// f(x, value): writes the integrand's components at abscissa x into `value`.
using VectorIntegrand = std::function<void(double x, std::span<double> value)>;

struct QuadratureOptions {
  /// Stop when, for every component i, the summed error estimate E_i satisfies
  /// E_i ≤ max(absolute_tolerance, relative_tolerance · |I_i|).
  double relative_tolerance = 1e-9;
  double absolute_tolerance = 0.0;
  /// Upper bound on the number of panels (each costs 15 evaluations); the
  /// result then reports converged = false with its honest error estimate.
  std::size_t max_panels = 4000;
};

struct QuadratureResult {
  std::vector<double> integral;        ///< I_i, one per component
  std::vector<double> error_estimate;  ///< E_i = Σ_panels |K15 − G7|, a conservative bound in practice
  std::size_t evaluations = 0;         ///< integrand calls
  std::size_t panels = 0;              ///< panels in the final partition
  bool converged = false;              ///< every component met its tolerance
};

/// ∫ f(x) dx over [breakpoints.front(), breakpoints.back()] for an integrand
/// with `components` components.
///
/// The interval is first cut at every breakpoint (place them where the integrand
/// has a kink, a jump or a sharp feature); each panel [a, b] is integrated by the
/// 15-point Kronrod rule K15 and the embedded 7-point Gauss rule G7,
///   ∫_a^b f ≈ h Σ_k w_k f(c + h x_k),   c = (a + b)/2, h = (b − a)/2,
/// and |K15 − G7| is taken as the panel's error (G7's error, so K15's is far
/// smaller for smooth f). The panel with the largest error relative to its
/// component's tolerance is bisected until the tolerance is met (QUADPACK's
/// QAG strategy). Breakpoints must be non-decreasing; zero-length pieces are skipped.
QuadratureResult integrate_adaptive(const VectorIntegrand& f, std::span<const double> breakpoints,
                                    std::size_t components, const QuadratureOptions& options = {});

}  // namespace zenith::atmosphere::reference
