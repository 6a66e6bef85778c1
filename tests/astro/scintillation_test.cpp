// Scintillation (astro/scintillation.h): the variance against the formula
// worked by hand, its scalings, the deviates' statistics and their determinism.
#include "astro/scintillation.h"

#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

namespace zenith::astro {
namespace {

TEST(Scintillation, VarianceIsOsbornsYoungFormulaWithTheFresnelScaleAndSaturation) {
  const ScintillationOptions eye;  // C_Y 1.5, 7 mm pupil, 0.1 s
  // The pupil is smaller than the Fresnel scale √(550e-9 m · 10 km) = 0.074162 m,
  // which takes its place: 1e-5 · 1.5² · 0.074162^(−4/3) / 0.1 = 0.0072213 at X = 1.
  const double zenith = scintillation_variance(eye, 1.0, 0.0, kEarthGroundRefractivity550);
  EXPECT_NEAR(zenith, 1e-5 * 2.25 * std::pow(std::sqrt(550e-9 * 1e4), -4.0 / 3.0) / 0.1, 1e-15);
  EXPECT_NEAR(zenith, 0.0072213, 5e-7);
  // (cos γ)⁻³ as X³; 2 km up, exp(−2 · 2000 / 8000); a 20 cm telescope's own D.
  EXPECT_NEAR(scintillation_variance(eye, 2.0, 0.0, kEarthGroundRefractivity550), 8.0 * zenith, 1e-15);
  EXPECT_NEAR(scintillation_variance(eye, 1.0, 2000.0, kEarthGroundRefractivity550), zenith * std::exp(-0.5), 1e-15);
  ScintillationOptions telescope = eye;
  telescope.pupil_mm = 200.0;
  EXPECT_NEAR(scintillation_variance(telescope, 1.0, 0.0, kEarthGroundRefractivity550),
              1e-5 * 2.25 * std::pow(0.2, -4.0 / 3.0) / 0.1, 1e-15);
  // Near the horizon it saturates at 1 (X = 10: 7.2 uncapped).
  EXPECT_DOUBLE_EQ(scintillation_variance(eye, 10.0, 0.0, kEarthGroundRefractivity550), 1.0);
  // Mars's air (n₀ − 1 ≈ 2.0e-6 at 636 Pa) twinkles (2e-6 / 2.7784e-4)² ≈ 5.2e-5 as much.
  EXPECT_NEAR(scintillation_variance(eye, 2.0, 0.0, 2.0e-6) / (8.0 * zenith), 5.1817e-5, 1e-8);
  EXPECT_THROW(scintillation_variance(eye, 0.5, 0.0, kEarthGroundRefractivity550), std::invalid_argument);
}

TEST(Scintillation, DeviatesAreStandardNormalAndTheFactorKeepsTheMeanFlux) {
  constexpr int kDraws = 200000;
  double sum = 0.0, sum2 = 0.0, f_sum = 0.0, f_sum2 = 0.0;
  constexpr double kVariance = 0.3;
  for (int i = 0; i < kDraws; ++i) {
    const double g = scintillation_normal(static_cast<std::uint64_t>(i % 997), i / 997);
    sum += g;
    sum2 += g * g;
    const double f = scintillation_factor(kVariance, g);
    f_sum += f;
    f_sum2 += f * f;
  }
  const double mean = sum / kDraws, variance = sum2 / kDraws - mean * mean;
  EXPECT_NEAR(mean, 0.0, 5.0 / std::sqrt(double(kDraws)));  // 5 standard errors
  EXPECT_NEAR(variance, 1.0, 5.0 * std::sqrt(2.0 / kDraws));
  // The log-normal factor: mean 1 (the star's flux is kept on average), variance σ_I².
  const double f_mean = f_sum / kDraws, f_variance = f_sum2 / kDraws - f_mean * f_mean;
  EXPECT_NEAR(f_mean, 1.0, 5.0 * std::sqrt(kVariance / kDraws));
  EXPECT_NEAR(f_variance, kVariance, 0.05 * kVariance);
  // Closed forms: g = 0 gives exp(−s²/2) with s² = ln 1.3; variance 0 gives 1 for any g.
  EXPECT_NEAR(scintillation_factor(kVariance, 0.0), 1.0 / std::sqrt(1.3), 1e-15);
  EXPECT_DOUBLE_EQ(scintillation_factor(0.0, 3.0), 1.0);
}

TEST(Scintillation, TheDrawIsAFunctionOfStarAndIntervalOnly) {
  EXPECT_EQ(scintillation_normal(42, 123456789), scintillation_normal(42, 123456789));
  EXPECT_NE(scintillation_normal(42, 123456789), scintillation_normal(42, 123456790));
  EXPECT_NE(scintillation_normal(42, 123456789), scintillation_normal(43, 123456789));
  // Bounded by what 53-bit uniforms allow.
  for (int i = 0; i < 10000; ++i) EXPECT_LE(std::abs(scintillation_normal(7, i)), kLargestScintillationNormal);
}

}  // namespace
}  // namespace zenith::astro
