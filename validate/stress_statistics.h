#pragma once
// Accumulators of the numerical-stability stress: value health (NaN, ±Inf,
// negative, transmittance above 1), distributions of relative errors, and the
// largest jump across the horizon with where it happened. Each is filled per
// chunk of samples on a worker thread and merged in chunk order, so the
// results do not depend on the thread count. No GL.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "validate/stress_geometry.h"

namespace zenith::validate {

/// Counts of checked values and of the bad ones among them.
struct ValueHealth {
  std::size_t values = 0;  ///< values checked (one per wavelength per query)
  std::size_t nan = 0;
  std::size_t inf = 0;
  std::size_t negative = 0;   ///< finite and < 0
  std::size_t above_one = 0;  ///< transmittances > 1 + 1e-12 (counted only where checked as transmittance)

  /// Checks one value; `transmittance`: it must also be at most 1.
  void check(double value, bool transmittance = false);
  std::size_t bad() const { return nan + inf + negative + above_one; }
  void merge(const ValueHealth& other);
};

/// Relative error with an absolute floor, per wavelength, the largest over wavelengths:
///   e = max_c |x_c − ref_c| / max(|ref_c|, floor)
/// so a radiance far below `floor` is judged by its absolute error relative to the floor.
double relative_error(const double* value, const double* reference, std::size_t channels, double floor);

/// A sample of errors and the label of the largest.
class ErrorDistribution {
 public:
  void add(double error, const std::string& where);
  void merge(const ErrorDistribution& other);
  std::size_t count() const { return errors_.size(); }
  /// The q-quantile (0 ≤ q ≤ 1) by the nearest-rank method; 0 for an empty sample.
  double quantile(double q) const;
  double median() const { return quantile(0.5); }
  double max() const { return max_; }
  const std::string& max_where() const { return max_where_; }

 private:
  std::vector<double> errors_;
  double max_ = 0.0;
  std::string max_where_;
};

/// The largest value seen and its label (first one kept on ties: deterministic merge order).
struct LargestValue {
  double value = 0.0;
  std::string where;
  void add(double v, const std::string& label) {
    if (v > value || (where.empty() && v >= value)) {
      value = v;
      where = label;
    }
  }
  void merge(const LargestValue& other) {
    if (!other.where.empty()) add(other.value, other.where);
  }
};

/// What one region collected on the CPU path.
struct RegionStatistics {
  std::size_t samples = 0;      ///< configurations
  ValueHealth health;           ///< every query of those configurations
  LargestValue horizon_jump;    ///< relative jump |L(+ε) − L(−ε)| / max(L(+ε), L(−ε), floor)
  ErrorDistribution reference;  ///< single scattering: tables vs exact quadrature

  void merge(const RegionStatistics& other);
};

using RegionTable = std::array<RegionStatistics, kRegionCount>;
void merge(RegionTable& into, const RegionTable& from);
RegionStatistics total(const RegionTable& table);

}  // namespace zenith::validate
