#include "atmosphere/density_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "atmosphere/constants.h"
#include "atmosphere/reference_data.h"

namespace zenith::atmosphere {
namespace {

double simpson(const std::function<double(double)>& f, double a, double b, int n = 20000) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4.0 : 2.0);
  return s * h / 3.0;
}

TEST(MonotoneCubicSpline, InterpolatesKnotsAndReproducesLines) {
  MonotoneCubicSpline s({0.0, 1.0, 3.0, 4.0}, {1.0, 2.0, 4.0, 5.0});  // a straight line y = x + 1
  for (double x : {0.0, 0.3, 1.0, 2.2, 3.0, 3.9, 4.0}) EXPECT_NEAR(s(x), x + 1.0, 1e-12) << x;
  EXPECT_NEAR(s.integral(0.0, 4.0), 12.0, 1e-12);
}

TEST(MonotoneCubicSpline, NoOvershootAtASharpPeak) {
  // Data with a sharp peak: a natural cubic spline would dip below zero beside it.
  MonotoneCubicSpline s({0, 1, 2, 3, 4, 5}, {0.0, 0.0, 1.0, 0.0, 0.0, 0.0});
  for (double x = 0.0; x <= 5.0; x += 0.001) {
    EXPECT_GE(s(x), 0.0) << x;
    EXPECT_LE(s(x), 1.0) << x;
  }
}

TEST(MonotoneCubicSpline, ExactIntegralMatchesQuadrature) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> x{0.0}, y{u(rng)};
  for (int i = 0; i < 20; ++i) {
    x.push_back(x.back() + 0.1 + u(rng));
    y.push_back(u(rng));
  }
  MonotoneCubicSpline s(x, y);
  EXPECT_NEAR(s.integral(0.0, x.back()), simpson([&](double t) { return s(t); }, 0.0, x.back()), 1e-6);
  EXPECT_NEAR(s.integral(1.3, 7.7), simpson([&](double t) { return s(t); }, 1.3, 7.7), 1e-6);
}

TEST(DensityProfile, ExponentialColumn) {
  const auto p = DensityProfile::exponential(8000.0);
  EXPECT_NEAR(p(8000.0), std::exp(-1.0), 1e-15);
  EXPECT_NEAR(p.column_m(0.0, 1e6), 8000.0, 1e-6);
  EXPECT_NEAR(p.column_m(1000.0, 5000.0), simpson([&](double h) { return p(h); }, 1000.0, 5000.0), 1e-6);
}

TEST(OzoneProfile, ColumnIsAbout345DobsonUnits) {
  double peak = 0.0;
  const DensityProfile ozone = us_standard_1976_profile("o3", &peak);
  const double column_DU = peak * ozone.column_m(0.0, 120e3) / kDobsonUnit_per_m2;
  EXPECT_NEAR(column_DU, 345.0, 1.5);
  // Peak near 22 km in the US Standard Atmosphere.
  double h_peak = 0.0, v_peak = 0.0;
  for (double h = 0.0; h < 60e3; h += 100.0)
    if (ozone(h) > v_peak) v_peak = ozone(h), h_peak = h;
  EXPECT_NEAR(h_peak, 22e3, 3e3);
  EXPECT_NEAR(v_peak, 1.0, 1e-12);
}

TEST(OzoneProfile, NonNegativeEverywhere) {
  const DensityProfile ozone = us_standard_1976_profile("o3", nullptr);
  for (double h = -100.0; h < 130e3; h += 7.0) EXPECT_GE(ozone(h), 0.0) << h;
}

TEST(OzoneCrossSection, TableValuesAndTemperature) {
  // ../shared/data/ozone_cross_sections_spectral.csv, 550 nm row.
  EXPECT_NEAR(ozone_cross_section_m2(550.0, 233.0), 3.3943e-25, 1e-31);
  EXPECT_NEAR(ozone_cross_section_m2(550.0, 293.0), 3.4197e-25, 1e-31);
  EXPECT_NEAR(ozone_cross_section_m2(550.0, 263.0), 0.5 * (3.3943e-25 + 3.4197e-25), 1e-31);
  // Between bins: linear interpolation.
  const double a = ozone_cross_section_m2(440.0, 233.0), b = ozone_cross_section_m2(450.0, 233.0);
  EXPECT_NEAR(ozone_cross_section_m2(445.0, 233.0), 0.5 * (a + b), 1e-35);
  bool covered = true;
  ozone_cross_section_m2(1000.0, 233.0, &covered);
  EXPECT_FALSE(covered);
}

}  // namespace
}  // namespace zenith::atmosphere
