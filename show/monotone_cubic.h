#pragma once
// Monotone piecewise-cubic interpolation (Fritsch & Carlson, "Monotone
// Piecewise Cubic Interpolation", SIAM J. Numer. Anal. 17(2), 1980).
//
// A cubic Hermite spline through (t_i, y_i) whose tangents are limited so that
// on every interval the curve is monotone whenever the data are: it never
// overshoots a key, never leaves [min y, max y] of the interval's two keys,
// and is flat where two neighbouring keys are equal. That is what show
// tracks need: an exposure, an altitude or a turbidity eases between keys
// without ringing past them (a cubic spline through 400 km and 2 m would dive
// below the ground).
#include <vector>

namespace zenith::show {

class MonotoneCubic {
 public:
  /// `t` strictly increasing, `y` the same size, both at least one value.
  /// Throws std::invalid_argument otherwise.
  MonotoneCubic(std::vector<double> t, std::vector<double> y);

  /// The interpolant at t, clamped to the first and last key outside them;
  /// exactly y_i at t_i.
  double operator()(double t) const;
  /// d/dt of the interpolant (0 outside the keys).
  double derivative(double t) const;

  const std::vector<double>& times() const { return t_; }
  const std::vector<double>& values() const { return y_; }

 private:
  std::vector<double> t_, y_;
  std::vector<double> slope_;  ///< tangent dy/dt at each key
};

}  // namespace zenith::show
