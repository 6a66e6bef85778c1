#include "atmosphere/density_profile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace zenith::atmosphere {

MonotoneCubicSpline::MonotoneCubicSpline(std::vector<double> x, std::vector<double> y)
    : x_(std::move(x)), y_(std::move(y)) {
  const std::size_t n = x_.size();
  if (n < 2 || y_.size() != n) throw std::invalid_argument("MonotoneCubicSpline: need >= 2 knots of equal length");
  for (std::size_t i = 1; i < n; ++i)
    if (!(x_[i] > x_[i - 1])) throw std::invalid_argument("MonotoneCubicSpline: x must increase strictly");

  // Secant slopes, then Fritsch–Butland harmonic-mean interior slopes, which
  // satisfy the Fritsch–Carlson monotonicity condition by construction; a knot
  // where the data turns (secants of opposite sign or zero) gets slope 0.
  std::vector<double> h(n - 1), delta(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = x_[i + 1] - x_[i];
    delta[i] = (y_[i + 1] - y_[i]) / h[i];
  }
  d_.assign(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    if (delta[i - 1] * delta[i] > 0.0) {
      const double w1 = 2.0 * h[i] + h[i - 1];
      const double w2 = h[i] + 2.0 * h[i - 1];
      d_[i] = (w1 + w2) / (w1 / delta[i - 1] + w2 / delta[i]);
    }
  }
  // End slopes: one-sided three-point estimate, limited to keep monotonicity.
  auto end_slope = [](double h0, double h1, double d0, double d1) {
    double d = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if (d * d0 <= 0.0) return 0.0;
    if (d0 * d1 <= 0.0 && std::abs(d) > std::abs(3.0 * d0)) return 3.0 * d0;
    return d;
  };
  if (n == 2) {
    d_[0] = d_[1] = delta[0];
  } else {
    d_[0] = end_slope(h[0], h[1], delta[0], delta[1]);
    d_[n - 1] = end_slope(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
  }
}

double MonotoneCubicSpline::operator()(double x) const {
  if (x <= x_.front()) return y_.front();
  if (x >= x_.back()) return y_.back();
  const std::size_t i = std::size_t(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin()) - 1;
  const double h = x_[i + 1] - x_[i];
  const double t = (x - x_[i]) / h;
  // Cubic Hermite basis.
  const double t2 = t * t, t3 = t2 * t;
  const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
  return h00 * y_[i] + h10 * h * d_[i] + h01 * y_[i + 1] + h11 * h * d_[i + 1];
}

double MonotoneCubicSpline::integral_from_start(double x) const {
  // Below the first knot the value is held at y.front().
  if (x <= x_.front()) return (x - x_.front()) * y_.front();
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < x_.size(); ++i) {
    const double h = x_[i + 1] - x_[i];
    if (x >= x_[i + 1]) {
      // ∫ of a cubic Hermite segment: h (y0 + y1)/2 + h² (d0 − d1)/12.
      sum += h * (y_[i] + y_[i + 1]) / 2.0 + h * h * (d_[i] - d_[i + 1]) / 12.0;
      continue;
    }
    // Partial segment: integrate the Hermite basis from 0 to t.
    const double t = (x - x_[i]) / h;
    const double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
    const double H00 = t4 / 2 - t3 + t, H10 = t4 / 4 - 2 * t3 / 3 + t2 / 2, H01 = -t4 / 2 + t3, H11 = t4 / 4 - t3 / 3;
    return sum + h * (H00 * y_[i] + H10 * h * d_[i] + H01 * y_[i + 1] + H11 * h * d_[i + 1]);
  }
  return sum + (x - x_.back()) * y_.back();
}

double MonotoneCubicSpline::integral(double a, double b) const {
  return integral_from_start(b) - integral_from_start(a);
}

DensityProfile DensityProfile::exponential(double scale_height_m) {
  if (!(scale_height_m > 0.0)) throw std::invalid_argument("DensityProfile: scale height must be > 0");
  DensityProfile p;
  p.kind_ = Kind::Exponential;
  p.scale_height_m_ = scale_height_m;
  return p;
}

DensityProfile DensityProfile::tabulated(std::vector<double> altitude_m, std::vector<double> relative_density,
                                         std::string source) {
  for (double v : relative_density)
    if (!(v >= 0.0) || !std::isfinite(v)) throw std::invalid_argument("DensityProfile: negative or non-finite density");
  DensityProfile p;
  p.kind_ = Kind::Tabulated;
  p.table_ = MonotoneCubicSpline(std::move(altitude_m), std::move(relative_density));
  p.source_ = std::move(source);
  return p;
}

double DensityProfile::operator()(double altitude_m) const {
  if (kind_ == Kind::Exponential) return std::exp(-altitude_m / scale_height_m_);
  return std::max(0.0, table_(altitude_m));
}

double DensityProfile::column_m(double from_m, double to_m) const {
  if (kind_ == Kind::Exponential)
    return scale_height_m_ * (std::exp(-from_m / scale_height_m_) - std::exp(-to_m / scale_height_m_));
  return table_.integral(from_m, to_m);
}

}  // namespace zenith::atmosphere
