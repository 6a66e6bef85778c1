#include "render/night/twinkle_sigma_table.h"

#include <algorithm>
#include <cmath>

#include "astro/scintillation.h"
#include "atmosphere/air_mass.h"
#include "core/units.h"

namespace zenith::render {

double twinkle_log_sigma(double per_cubed_air_mass, double mu) {
  const double elevation_deg = std::asin(std::clamp(mu, 0.0, 1.0)) * core::kRadToDeg;
  return astro::scintillation_log_sigma(
      astro::scintillation_variance_at(per_cubed_air_mass, atmosphere::pickering_air_mass(elevation_deg)));
}

TwinkleSigmaTable::TwinkleSigmaTable(double per_cubed_air_mass) : per_cubed_air_mass_(per_cubed_air_mass) {
  // Where σ_I² reaches its cap of 1 (X falls as μ rises): s is √ln 2 below, smooth above.
  const auto capped = [&](double mu) {
    const double elevation_deg = std::asin(mu) * core::kRadToDeg;
    const double x = atmosphere::pickering_air_mass(elevation_deg);
    return per_cubed_air_mass_ * (x * x * x) >= 1.0;
  };
  if (capped(1.0)) {
    mu_cap_ = 1.0;
  } else if (capped(0.0)) {
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 64; ++k) (capped(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
    mu_cap_ = hi;
  }
  s_cap_ = astro::scintillation_log_sigma(1.0);
  span_ = 1.0 - mu_cap_;
  s_.resize(kNodes + 1);
  for (std::size_t j = 0; j <= kNodes; ++j) {
    const double t = double(j) / double(kNodes);
    s_[j] = exact(mu_cap_ + span_ * t * t);
  }
  std::vector<double> second(kNodes + 1, 0.0);
  for (std::size_t j = 1; j < kNodes; ++j) second[j] = std::abs(s_[j - 1] - 2.0 * s_[j] + s_[j + 1]);
  second[0] = second[1];
  second[kNodes] = second[kNodes - 1];
  bound_.resize(kNodes);
  for (std::size_t j = 0; j < kNodes; ++j) {
    bound_[j] = 2.0 * 0.25 * (second[j] + second[j + 1]) + 1e-15;
    largest_bound_ = std::max(largest_bound_, bound_[j]);
  }
}

double TwinkleSigmaTable::exact(double mu) const { return twinkle_log_sigma(per_cubed_air_mass_, mu); }

double TwinkleSigmaTable::operator()(double mu) const {
  if (mu_cap_ > 0.0 && !(mu > mu_cap_)) return s_cap_;
  const double x = std::sqrt((std::clamp(mu, mu_cap_, 1.0) - mu_cap_) / span_) * double(kNodes);
  const std::size_t j = std::min(static_cast<std::size_t>(x), kNodes - 1);
  const double f = x - double(j);
  return s_[j] + (s_[j + 1] - s_[j]) * f;
}

double TwinkleSigmaTable::bound_at(double mu) const {
  if (mu_cap_ > 0.0 && !(mu > mu_cap_)) return 1e-15;
  const double x = std::sqrt((std::clamp(mu, mu_cap_, 1.0) - mu_cap_) / span_) * double(kNodes);
  return bound_[std::min(static_cast<std::size_t>(x), kNodes - 1)];
}

}  // namespace zenith::render
