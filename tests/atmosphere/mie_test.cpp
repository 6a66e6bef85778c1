#include "atmosphere/mie.h"

#include <gtest/gtest.h>

#include <cmath>

#include "atmosphere/constants.h"

namespace zenith::atmosphere {
namespace {

/// Eq. (19) exactly as printed, for comparison at moderate ρ where it is well conditioned.
double printed_eq19(double lambda_nm, double m, double k, double r) {
  const double rho = 4.0 * kPi * r * (m - 1.0) / (lambda_nm * 1e-9);
  const double beta = std::atan(k / (m - 1.0));
  const double c = std::cos(beta) / rho;
  const double e = std::exp(-rho * std::tan(beta));
  return 2.0 - 4.0 * e * c * std::sin(rho - beta) - 4.0 * e * c * c * std::cos(rho - 2.0 * beta) +
         4.0 * c * c * std::cos(2.0 * beta);
}

TEST(Mie, TurbidityScatteringClosedForm) {
  // T = 2, ν = 4, K = 0.0092, λ = 550 nm: 0.434 · 0.65e-16 · π · (2π/550e-9)² · 0.0092.
  const double k2 = std::pow(2.0 * kPi / 550e-9, 2.0);
  const double expected = 0.434 * 0.65e-16 * kPi * k2 * 0.0092;
  EXPECT_NEAR(mie_scattering_from_turbidity(550.0, 2.0, 4.0, 0.0092), expected, expected * 1e-12);
  EXPECT_NEAR(expected, 1.0641e-4, 0.0001e-4);
  EXPECT_EQ(mie_scattering_from_turbidity(550.0, 1.0, 4.0, 0.0092), 0.0);  // T = 1: no aerosol
  // ν = 3 gives a λ^-1 law.
  EXPECT_NEAR(
      mie_scattering_from_turbidity(400.0, 3.0, 3.0, 0.01) / mie_scattering_from_turbidity(800.0, 3.0, 3.0, 0.01), 2.0,
      1e-12);
}

TEST(Mie, AnomalousDiffractionMatchesPrintedFormula) {
  for (double r : {0.3e-6, 1.0e-6, 1.6e-6, 5e-6})
    for (double k : {0.0, 0.001, 0.013, 0.3}) {
      const double q = anomalous_diffraction_extinction_efficiency(550.0, {1.52, k}, r);
      EXPECT_NEAR(q, printed_eq19(550.0, 1.52, k, r), 1e-10) << "r=" << r << " k=" << k;
    }
}

TEST(Mie, AnomalousDiffractionLimits) {
  // Non-absorbing, small ρ: Q → ρ²/2 (where eq. 19 as printed loses all digits).
  const double r = 1e-10, m = 1.33, lambda = 500.0;
  const double rho = 4.0 * kPi * r * (m - 1.0) / (lambda * 1e-9);
  EXPECT_NEAR(anomalous_diffraction_extinction_efficiency(lambda, {m, 0.0}, r), rho * rho / 2.0, rho * rho * 1e-6);
  // Large spheres: extinction paradox, Q → 2.
  EXPECT_NEAR(anomalous_diffraction_extinction_efficiency(lambda, {m, 0.0}, 1e-3), 2.0, 1e-3);
  // First maximum of the non-absorbing ADA curve: Q ≈ 3.17 at ρ ≈ 4.09.
  const double r_peak = 4.09 * lambda * 1e-9 / (4.0 * kPi * (m - 1.0));
  EXPECT_NEAR(anomalous_diffraction_extinction_efficiency(lambda, {m, 0.0}, r_peak), 3.17, 0.01);
  // Continuity across the series/closed-form switch at |w| = 0.25 (the ±1e-9
  // change of radius itself moves Q by ~1.2e-10).
  const double r_switch = 0.25 * lambda * 1e-9 / (4.0 * kPi * (m - 1.0));
  EXPECT_NEAR(anomalous_diffraction_extinction_efficiency(lambda, {m, 0.0}, r_switch * (1 - 1e-9)),
              anomalous_diffraction_extinction_efficiency(lambda, {m, 0.0}, r_switch * (1 + 1e-9)), 2e-10);
}

TEST(Mie, AnomalousDiffractionAbsorptionBounds) {
  EXPECT_EQ(anomalous_diffraction_absorption_efficiency(550.0, 0.0, 1e-6), 0.0);
  EXPECT_NEAR(anomalous_diffraction_absorption_efficiency(550.0, 1.0, 1e-3), 1.0, 1e-6);  // opaque: Q_abs → 1
  for (double k : {0.001, 0.013, 0.1}) {
    const double qa = anomalous_diffraction_absorption_efficiency(550.0, k, 1.6e-6);
    const double qe = anomalous_diffraction_extinction_efficiency(550.0, {1.52, k}, 1.6e-6);
    EXPECT_GT(qa, 0.0);
    EXPECT_LT(qa, qe);  // single-scattering albedo in (0, 1)
  }
}

TEST(Mie, MeanRadiusExtinction) {
  const double r = 1.6e-6, N = 2.8e6;
  const double q = anomalous_diffraction_extinction_efficiency(550.0, {1.52, 0.006}, r);
  EXPECT_NEAR(mie_extinction_anomalous_diffraction(550.0, {1.52, 0.006}, r, N), kPi * r * r * q * N, 1e-18);
}

}  // namespace
}  // namespace zenith::atmosphere
