#include "atmosphere/tabulated_phase.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/units.h"

namespace zenith::atmosphere {

namespace {

constexpr std::size_t K = TabulatedPhase::kSamples;

double grid_u(std::size_t k) { return static_cast<double>(k) / static_cast<double>(K - 1); }

/// log P interpolated linearly in θ between the given angles.
double column_at(const std::vector<double>& angles_deg, const std::vector<double>& values, double theta_deg) {
  const auto hi = std::upper_bound(angles_deg.begin(), angles_deg.end(), theta_deg);
  if (hi == angles_deg.begin()) return values.front();
  if (hi == angles_deg.end()) return values.back();
  const std::size_t j = static_cast<std::size_t>(hi - angles_deg.begin()) - 1;
  const double t = (theta_deg - angles_deg[j]) / (angles_deg[j + 1] - angles_deg[j]);
  return std::exp(std::log(values[j]) + t * (std::log(values[j + 1]) - std::log(values[j])));
}

/// ∫ P u du over the segment [u0, u0 + h] where P goes linearly from p0 to p1.
double segment_moment(double u0, double h, double p0, double p1) {
  const double dp = p1 - p0;
  return h * (p0 * u0 + p0 * h / 2.0 + dp * u0 / 2.0 + dp * h / 3.0);
}

}  // namespace

TabulatedPhase::TabulatedPhase(const std::vector<double>& angles_deg, const std::vector<Column>& given,
                               const std::vector<double>& wavelengths_nm) {
  if (angles_deg.size() < 2) throw std::invalid_argument("a tabulated phase needs at least 2 angles");
  if (angles_deg.front() != 0.0 || angles_deg.back() != 180.0)
    throw std::invalid_argument("a tabulated phase's angles must run from 0 to 180 degrees");
  for (std::size_t j = 1; j < angles_deg.size(); ++j)
    if (!(angles_deg[j] > angles_deg[j - 1]))
      throw std::invalid_argument("a tabulated phase's angles must be strictly increasing");
  if (given.empty()) throw std::invalid_argument("a tabulated phase needs at least one wavelength");
  std::vector<Column> columns = given;
  std::sort(columns.begin(), columns.end(),
            [](const Column& a, const Column& b) { return a.wavelength_nm < b.wavelength_nm; });
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (!(columns[c].wavelength_nm > 0.0) || (c > 0 && columns[c].wavelength_nm == columns[c - 1].wavelength_nm))
      throw std::invalid_argument("a tabulated phase's wavelengths must be positive and distinct");
    if (columns[c].values.size() != angles_deg.size())
      throw std::invalid_argument("a tabulated phase's column at " + std::to_string(columns[c].wavelength_nm) +
                                  " nm has " + std::to_string(columns[c].values.size()) + " values for " +
                                  std::to_string(angles_deg.size()) + " angles");
    for (double v : columns[c].values)
      if (!(v > 0.0) || !std::isfinite(v))
        throw std::invalid_argument("a tabulated phase's values must be positive and finite");
  }

  // Each given column on the u grid.
  std::vector<std::vector<double>> on_grid(columns.size(), std::vector<double>(K));
  for (std::size_t c = 0; c < columns.size(); ++c)
    for (std::size_t k = 0; k < K; ++k)
      on_grid[c][k] = column_at(angles_deg, columns[c].values, 2.0 * std::asin(grid_u(k)) * 180.0 / core::kPi);

  const std::size_t n = wavelengths_nm.size();
  samples_.resize(n * K);
  segment_cdf_.resize(n * K);
  integral_as_given_.resize(n);
  asymmetry_.resize(n);
  const double h = grid_u(1);
  for (std::size_t i = 0; i < n; ++i) {
    double* p = &samples_[i * K];
    // Linear in λ between the bracketing columns, the nearest one outside.
    const double wl = wavelengths_nm[i];
    std::size_t hi = 0;
    while (hi < columns.size() && columns[hi].wavelength_nm < wl) ++hi;
    for (std::size_t k = 0; k < K; ++k) {
      if (hi == 0) {
        p[k] = on_grid.front()[k];
      } else if (hi == columns.size()) {
        p[k] = on_grid.back()[k];
      } else {
        const double t =
            (wl - columns[hi - 1].wavelength_nm) / (columns[hi].wavelength_nm - columns[hi - 1].wavelength_nm);
        p[k] = on_grid[hi - 1][k] + t * (on_grid[hi][k] - on_grid[hi - 1][k]);
      }
    }
    double moment = 0.0;
    for (std::size_t k = 0; k + 1 < K; ++k) moment += segment_moment(grid_u(k), h, p[k], p[k + 1]);
    const double integral = 8.0 * core::kPi * moment;
    integral_as_given_[i] = integral;
    for (std::size_t k = 0; k < K; ++k) p[k] /= integral;

    double* cdf = &segment_cdf_[i * K];
    cdf[0] = 0.0;
    for (std::size_t k = 0; k + 1 < K; ++k)
      cdf[k + 1] = cdf[k] + 8.0 * core::kPi * segment_moment(grid_u(k), h, p[k], p[k + 1]);
    cdf[K - 1] = 1.0;  // the sum is 1 to rounding; the last segment ends the distribution

    // g = 8π ∫ P(u) (1 − 2u²) u du: a degree-4 polynomial on each segment, so
    // 3-point Gauss–Legendre is exact.
    constexpr double kNode = 0.7745966692414834, kW0 = 8.0 / 9.0, kW1 = 5.0 / 9.0;
    double g = 0.0;
    for (std::size_t k = 0; k + 1 < K; ++k)
      for (const auto& [x, w] : {std::pair{0.0, kW0}, std::pair{-kNode, kW1}, std::pair{kNode, kW1}}) {
        const double t = 0.5 * (x + 1.0);
        const double u = grid_u(k) + h * t;
        g += 0.5 * w * h * (p[k] + t * (p[k + 1] - p[k])) * (1.0 - 2.0 * u * u) * u;
      }
    asymmetry_[i] = 8.0 * core::kPi * g;
  }
}

std::size_t TabulatedPhase::segment(double cos_theta, double* fraction) {
  const double u = std::sqrt(std::max(0.0, 0.5 - 0.5 * cos_theta));
  const double x = std::min(u, 1.0) * static_cast<double>(K - 1);
  const std::size_t k = std::min(static_cast<std::size_t>(x), K - 2);
  *fraction = x - static_cast<double>(k);
  return k;
}

double TabulatedPhase::operator()(std::size_t i, double cos_theta) const {
  double f = 0.0;
  const std::size_t k = segment(cos_theta, &f);
  const double* p = &samples_[i * K];
  return p[k] + f * (p[k + 1] - p[k]);
}

double TabulatedPhase::sample_cosine(std::size_t i, double u_segment, double u) const {
  const double* cdf = &segment_cdf_[i * K];
  const std::size_t k =
      std::clamp<std::size_t>(static_cast<std::size_t>(std::upper_bound(cdf, cdf + K, u_segment) - cdf), 1, K - 1) - 1;
  const double a = grid_u(k) * grid_u(k), b = grid_u(k + 1) * grid_u(k + 1);
  return std::clamp(1.0 - 2.0 * (a + u * (b - a)), -1.0, 1.0);
}

double TabulatedPhase::proposal_pdf(std::size_t i, double cos_theta) const {
  double f = 0.0;
  const std::size_t k = segment(cos_theta, &f);
  const double* cdf = &segment_cdf_[i * K];
  const double area = 4.0 * core::kPi * (grid_u(k + 1) * grid_u(k + 1) - grid_u(k) * grid_u(k));
  return (cdf[k + 1] - cdf[k]) / area;
}

}  // namespace zenith::atmosphere
