#include "atmosphere/rayleigh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "atmosphere/constants.h"
#include "tests/atmosphere/test_util.h"

namespace zenith::atmosphere {
namespace {

TEST(Rayleigh, KingFactorKnownValues) {
  test::expect_published_values(king_factor, {{0.0279, 1.04806, 5e-6}, {0.09, 1.1676, 5e-5}});
  EXPECT_DOUBLE_EQ(king_factor(0.0), 1.0);
}

TEST(Rayleigh, StandardAirIndexMatchesPenndorfTable) {
  // Penndorf (1957) standard air; Table 1 of the paper prints 1.00027598 and
  // 1.00027783 at 680 and 550 nm. Its 440 nm entry, 1.00028276, is the index at
  // 400 nm (a slip, docs/physics.md); at 440 nm it is 1.00028091.
  test::expect_published_values(
      standard_air_refractive_index,
      {{680.0, 1.00027598, 5e-9}, {550.0, 1.00027783, 5e-9}, {440.0, 1.00028091, 5e-9}, {400.0, 1.00028276, 5e-9}});
}

TEST(Rayleigh, ScatteringCoefficientOfStandardAir) {
  // n from Penndorf's table, N = 2.547e25 m^-3, δ = 0.0279 → (4.849, 11.483, 28.66)e-6 m^-1.
  const double N = 2.547e25, delta = 0.0279;
  EXPECT_NEAR(rayleigh_scattering_coefficient(680.0, 1.00027598, N, delta), 4.849e-6, 0.002e-6);
  EXPECT_NEAR(rayleigh_scattering_coefficient(550.0, 1.00027783, N, delta), 11.483e-6, 0.005e-6);
  EXPECT_NEAR(rayleigh_scattering_coefficient(440.0, 1.00028091, N, delta), 28.66e-6, 0.01e-6);
  for (double wl : {680.0, 550.0, 440.0})
    EXPECT_NEAR(
        rayleigh_scattering_coefficient(wl, standard_air_refractive_index(wl), N, delta),
        rayleigh_scattering_coefficient(wl, std::round(standard_air_refractive_index(wl) * 1e8) / 1e8, N, delta),
        0.001e-6);
}

TEST(Rayleigh, ScatteringFollowsInverseFourthPowerAtFixedIndex) {
  const double a = rayleigh_scattering_coefficient(400.0, 1.0003, 2.5e25, 0.03);
  const double b = rayleigh_scattering_coefficient(800.0, 1.0003, 2.5e25, 0.03);
  EXPECT_NEAR(a / b, 16.0, 1e-12);
}

TEST(Rayleigh, ScaledCoefficientIsCrossSectionTimesDensity) {
  // Same gas at a tenth of the density scatters a tenth as much.
  const double full = rayleigh_scattering_coefficient(550.0, 1.00045019, 2.6868e25, 0.09);
  EXPECT_NEAR(rayleigh_scattering_coefficient_scaled(550.0, 1.00045019, 2.6868e25, 2.6868e24, 0.09), full / 10.0,
              1e-18);
  // CO2 cross section at 550 nm ≈ 1.2e-30 m^2 (Sneep & Ubachs 2005 give 1.24e-30 at 532 nm).
  EXPECT_NEAR(full / 2.6868e25, 1.19e-30, 0.03e-30);
}

TEST(Rayleigh, SmallParticleAbsorptionClosedForm) {
  // For n = m + ik, Im((n²−1)/(n²+2)) = 6 m k / ((m² − k² + 2)² + 4 m² k²).
  const double m = 1.5, k = 0.01, r = 1e-8, N = 1e20, lambda_nm = 500.0;
  const double im = 6.0 * m * k / ((m * m - k * k + 2.0) * (m * m - k * k + 2.0) + 4.0 * m * m * k * k);
  const double expected = 8.0 * kPi * kPi * r * r * r * N / (lambda_nm * 1e-9) * im;
  EXPECT_NEAR(small_particle_absorption_coefficient(lambda_nm, {m, k}, r, N), expected, expected * 1e-12);
  EXPECT_EQ(small_particle_absorption_coefficient(lambda_nm, {m, 0.0}, r, N), 0.0);
}

TEST(Rayleigh, IdealGasRelations) {
  // Standard air: 101325 Pa, 288.15 K → 2.5469e25 m^-3; H = R T/(M g) = 8434.5 m.
  EXPECT_NEAR(number_density_from_pressure(101325.0, 288.15), 2.5469e25, 0.0001e25);
  EXPECT_NEAR(scale_height(288.15, 0.0289644, 9.80665), 8434.5, 0.5);
  // 1.225 kg/m^3 of air (M = 28.9644 g/mol) is the same gas.
  EXPECT_NEAR(number_density_from_mass_density(1.225, 0.0289644), 2.5469e25, 0.001e25);
}

}  // namespace
}  // namespace zenith::atmosphere
