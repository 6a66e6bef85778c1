#include "validate/stress_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace zenith::validate {

void ValueHealth::check(double value, bool transmittance) {
  ++values;
  if (std::isnan(value)) {
    ++nan;
  } else if (std::isinf(value)) {
    ++inf;
  } else if (value < 0.0) {
    ++negative;
  } else if (transmittance && value > 1.0 + 1e-12) {
    ++above_one;
  }
}

void ValueHealth::merge(const ValueHealth& o) {
  values += o.values;
  nan += o.nan;
  inf += o.inf;
  negative += o.negative;
  above_one += o.above_one;
}

double relative_error(const double* value, const double* reference, std::size_t channels, double floor) {
  double worst = 0.0;
  for (std::size_t c = 0; c < channels; ++c) {
    const double e = std::abs(value[c] - reference[c]) / std::max(std::abs(reference[c]), floor);
    // A NaN anywhere must surface as the worst error, not vanish in std::max.
    if (!(e <= worst)) worst = std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
  }
  return worst;
}

void ErrorDistribution::add(double error, const std::string& where) {
  errors_.push_back(error);
  if (errors_.size() == 1 || error > max_) {
    max_ = error;
    max_where_ = where;
  }
}

void ErrorDistribution::merge(const ErrorDistribution& o) {
  if (o.errors_.empty()) return;
  const bool take_max = errors_.empty() || o.max_ > max_;
  errors_.insert(errors_.end(), o.errors_.begin(), o.errors_.end());
  if (take_max) {
    max_ = o.max_;
    max_where_ = o.max_where_;
  }
}

double ErrorDistribution::quantile(double q) const {
  if (errors_.empty()) return 0.0;
  std::vector<double> sorted = errors_;
  // Nearest rank: the smallest value with at least q·n values at or below it.
  const auto rank = static_cast<std::size_t>(std::ceil(std::clamp(q, 0.0, 1.0) * double(sorted.size())));
  const std::size_t k = rank == 0 ? 0 : rank - 1;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
  return sorted[k];
}

void RegionStatistics::merge(const RegionStatistics& o) {
  samples += o.samples;
  health.merge(o.health);
  horizon_jump.merge(o.horizon_jump);
  reference.merge(o.reference);
}

void merge(RegionTable& into, const RegionTable& from) {
  for (std::size_t i = 0; i < kRegionCount; ++i) into[i].merge(from[i]);
}

RegionStatistics total(const RegionTable& table) {
  RegionStatistics t;
  for (const auto& r : table) t.merge(r);
  return t;
}

}  // namespace zenith::validate
