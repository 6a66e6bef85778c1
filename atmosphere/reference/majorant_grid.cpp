#include "atmosphere/reference/majorant_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace zenith::atmosphere::reference {

namespace {

struct Range {
  double minimum, maximum;
};

/// Bounds of ρ(h) over [h0, h1] (see the header for why they are safe).
Range profile_range(const DensityProfile& profile, double h0, double h1) {
  Range range{std::min(profile(h0), profile(h1)), std::max(profile(h0), profile(h1))};
  auto include = [&](double h) {
    const double rho = profile(h);
    range.minimum = std::min(range.minimum, rho);
    range.maximum = std::max(range.maximum, rho);
  };
  static constexpr int kSamples = 33;
  for (int k = 1; k < kSamples - 1; ++k) include(h0 + (h1 - h0) * k / (kSamples - 1));
  if (profile.kind() == DensityProfile::Kind::Tabulated)
    for (double knot : profile.table().knots_x())
      if (knot > h0 && knot < h1) include(knot);
  return range;
}

}  // namespace

MajorantGrid::MajorantGrid(const AtmosphereModel& model, std::size_t shell_count)
    : wavelength_count_(model.wavelength_count()),
      ground_radius_m_(model.ground_radius_m),
      shell_thickness_m_(model.atmosphere_height_m() / double(shell_count)) {
  if (shell_count == 0) throw std::invalid_argument("MajorantGrid: need at least one shell");
  const std::size_t n = wavelength_count_;
  majorant_m1_.assign(shell_count * n, 0.0);
  minorant_m1_.assign(shell_count * n, 0.0);
  for (std::size_t k = 0; k <= shell_count; ++k)
    boundary_radius_m_.push_back(k == shell_count ? model.top_radius_m
                                                  : model.ground_radius_m + shell_thickness_m_ * double(k));
  static constexpr double kWidening_m = 1.0, kMargin = 0.01;
  for (std::size_t k = 0; k < shell_count; ++k) {
    const double h0 = shell_thickness_m_ * double(k) - kWidening_m;
    const double h1 = shell_thickness_m_ * double(k + 1) + kWidening_m;
    const Range rayleigh = profile_range(model.rayleigh_density, h0, h1);
    const Range mie = model.has_mie() ? profile_range(model.mie_density, h0, h1) : Range{0.0, 0.0};
    for (std::size_t i = 0; i < n; ++i) {
      majorant_m1_[k * n + i] =
          model.rayleigh_scattering_m1[i] * rayleigh.maximum + model.mie_extinction_m1[i] * mie.maximum;
      minorant_m1_[k * n + i] =
          model.rayleigh_scattering_m1[i] * rayleigh.minimum + model.mie_extinction_m1[i] * mie.minimum;
    }
    for (const Absorber& a : model.absorbers) {
      const Range absorber = profile_range(a.profile, h0, h1);
      for (std::size_t i = 0; i < n; ++i) {
        majorant_m1_[k * n + i] += a.absorption_m1[i] * absorber.maximum;
        minorant_m1_[k * n + i] += a.absorption_m1[i] * absorber.minimum;
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      majorant_m1_[k * n + i] *= 1.0 + kMargin;
      minorant_m1_[k * n + i] = std::max(0.0, minorant_m1_[k * n + i] * (1.0 - kMargin));
    }
  }
}

std::size_t MajorantGrid::shell_of_radius(double r_m) const {
  const double x = (r_m - ground_radius_m_) / shell_thickness_m_;
  if (!(x > 0.0)) return 0;
  return std::min(std::size_t(x), shell_count() - 1);
}

}  // namespace zenith::atmosphere::reference
