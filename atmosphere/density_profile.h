#pragma once
// Vertical density profiles: the relative number density ρ(h)/ρ_ref of a
// constituent at altitude h above the ground. Coefficients are given at the
// reference density and scaled by the profile, e.g. β(h) = β_ref · ρ(h).
#include <string>
#include <vector>

namespace zenith::atmosphere {

/// Monotone piecewise-cubic Hermite interpolant (Fritsch–Carlson 1980, "PCHIP").
/// Between two knots it never leaves the range of their values, so a profile
/// built from non-negative data is non-negative everywhere, and it has no
/// overshoot at the sharp ozone peak that a natural cubic spline would add.
class MonotoneCubicSpline {
 public:
  MonotoneCubicSpline() = default;
  /// `x` strictly increasing, at least two knots.
  MonotoneCubicSpline(std::vector<double> x, std::vector<double> y);

  /// Value at x; clamped to the end values outside [x.front(), x.back()].
  double operator()(double x) const;
  /// Exact integral of the interpolant over [a, b] (clamped as above).
  double integral(double a, double b) const;

  const std::vector<double>& knots_x() const { return x_; }
  const std::vector<double>& knots_y() const { return y_; }
  const std::vector<double>& slopes() const { return d_; }

 private:
  double integral_from_start(double x) const;
  std::vector<double> x_, y_, d_;
};

class DensityProfile {
 public:
  enum class Kind { Exponential, Tabulated };

  /// Hydrostatic (isothermal) profile ρ(h) = exp(−h/H), H in metres.
  static DensityProfile exponential(double scale_height_m);
  /// Tabulated profile through (altitude_m, relative density) knots, interpolated
  /// by a monotone cubic; zero above the last knot's altitude is *not* assumed:
  /// the last value is held (tables end where the density is negligible).
  static DensityProfile tabulated(std::vector<double> altitude_m, std::vector<double> relative_density,
                                  std::string source);

  Kind kind() const { return kind_; }
  double scale_height_m() const { return scale_height_m_; }
  const MonotoneCubicSpline& table() const { return table_; }
  const std::string& source() const { return source_; }

  /// Relative density at altitude h [m] (h ≥ 0 is above the ground).
  double operator()(double altitude_m) const;
  /// ∫ ρ(h) dh from `from_m` to `to_m` [m]: the vertical column in metres of
  /// reference-density gas. Exact for both kinds.
  double column_m(double from_m, double to_m) const;

 private:
  Kind kind_ = Kind::Exponential;
  double scale_height_m_ = 0.0;
  MonotoneCubicSpline table_;
  std::string source_;
};

}  // namespace zenith::atmosphere
