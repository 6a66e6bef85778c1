#pragma once
// One interval of the rule that integrates scattering along a ray.
#include <cmath>

#include "atmosphere/lut/precompute_options.h"

namespace zenith::atmosphere::lut {

/// ∫ f over an interval of length h from its end values f0, f1 ≥ 0.
///  * Trapezoid: h (f0 + f1)/2.
///  * LogLinear: f interpolated as an exponential, ∫ = h (f1 − f0)/ln(f1/f0),
///    exact when f decays exponentially across the interval (density profiles
///    and transmittance along steep rays); trapezoid where an end value is 0,
///    and a series where f0 ≈ f1.
inline double integrate_interval(double f0, double f1, double h, PrecomputeOptions::Quadrature rule) {
  if (rule == PrecomputeOptions::Quadrature::Trapezoid || f0 <= 0.0 || f1 <= 0.0) return 0.5 * h * (f0 + f1);
  const double x = std::log(f1 / f0);
  if (std::abs(x) < 1e-4) return h * f0 * (1.0 + x / 2.0 + x * x / 6.0);  // (e^x − 1)/x
  return h * (f1 - f0) / x;
}

}  // namespace zenith::atmosphere::lut
