#include "show/monotone_cubic.h"

#include <cmath>
#include <stdexcept>

#include "show/key_span.h"

namespace zenith::show {

MonotoneCubic::MonotoneCubic(std::vector<double> t, std::vector<double> y)
    : t_(std::move(t)), y_(std::move(y)), slope_(t_.size(), 0.0) {
  if (t_.empty() || t_.size() != y_.size())
    throw std::invalid_argument("MonotoneCubic: needs as many values as times, at least one");
  for (std::size_t i = 1; i < t_.size(); ++i)
    if (!(t_[i] > t_[i - 1])) throw std::invalid_argument("MonotoneCubic: times must be strictly increasing");
  const std::size_t n = t_.size();
  if (n < 2) return;

  // 1. Secants δ_k = (y_{k+1} − y_k) / h_k of each interval.
  std::vector<double> secant(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) secant[k] = (y_[k + 1] - y_[k]) / (t_[k + 1] - t_[k]);

  // 2. Initial tangents: one-sided secants at the ends; inside, the mean of the
  //    two neighbouring secants, or 0 at a local extremum (secants of
  //    different sign, or one of them 0) so the extremum stays at the key.
  slope_[0] = secant[0];
  slope_[n - 1] = secant[n - 2];
  for (std::size_t k = 1; k + 1 < n; ++k)
    slope_[k] = secant[k - 1] * secant[k] > 0.0 ? 0.5 * (secant[k - 1] + secant[k]) : 0.0;

  // 3. Fritsch–Carlson limiter. With α = m_k / δ_k and β = m_{k+1} / δ_k, the
  //    cubic on the interval is monotone if (α, β) lies in the circle
  //    α² + β² ≤ 9 (a sufficient part of their monotonicity region); scale both
  //    tangents back onto it when outside. Flat intervals get flat tangents.
  for (std::size_t k = 0; k + 1 < n; ++k) {
    if (secant[k] == 0.0) {
      slope_[k] = slope_[k + 1] = 0.0;
      continue;
    }
    const double alpha = slope_[k] / secant[k], beta = slope_[k + 1] / secant[k];
    const double radius_squared = alpha * alpha + beta * beta;
    if (radius_squared > 9.0) {
      const double tau = 3.0 / std::sqrt(radius_squared);
      slope_[k] = tau * alpha * secant[k];
      slope_[k + 1] = tau * beta * secant[k];
    }
  }
}

double MonotoneCubic::operator()(double t) const {
  const KeySpan span = locate(t_, t);
  const std::size_t k = span.segment;
  if (t_.size() < 2 || span.fraction == 0.0) return y_[k];
  if (span.fraction == 1.0) return y_[k + 1];
  // Cubic Hermite basis on s ∈ [0, 1] with tangents scaled by the interval h.
  const double s = span.fraction, h = t_[k + 1] - t_[k];
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0, h10 = s3 - 2.0 * s2 + s;
  const double h01 = -2.0 * s3 + 3.0 * s2, h11 = s3 - s2;
  return h00 * y_[k] + h10 * h * slope_[k] + h01 * y_[k + 1] + h11 * h * slope_[k + 1];
}

double MonotoneCubic::derivative(double t) const {
  if (t_.size() < 2 || t < t_.front() || t > t_.back()) return 0.0;
  const KeySpan span = locate(t_, t);
  const std::size_t k = span.segment;
  const double s = span.fraction, h = t_[k + 1] - t_[k];
  const double s2 = s * s;
  // d/ds of the basis, divided by h for d/dt.
  const double d00 = 6.0 * s2 - 6.0 * s, d10 = 3.0 * s2 - 4.0 * s + 1.0;
  const double d01 = -6.0 * s2 + 6.0 * s, d11 = 3.0 * s2 - 2.0 * s;
  return (d00 * y_[k] + d01 * y_[k + 1]) / h + d10 * slope_[k] + d11 * slope_[k + 1];
}

}  // namespace zenith::show
