// The spherical-harmonic pieces of the scattering density (atmosphere/lut/
// spherical_harmonics.h) against closed forms: orthonormality of the
// normalised Legendre functions, Legendre moments of Henyey–Greenstein (g^l)
// and of the classic Rayleigh phase (1, 0, 1/10), and the horizon-split rule.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "atmosphere/constants.h"
#include "atmosphere/lut/gauss_legendre.h"
#include "atmosphere/lut/spherical_harmonics.h"
#include "atmosphere/phase_functions.h"

namespace zenith::atmosphere::lut {
namespace {

TEST(SphericalHarmonics, NormalisedLegendreFunctionsAreOrthonormal) {
  // 2π ∫ P̄_l^m P̄_k^m dx = δ_lk (the cos(mφ) factor and c_m give the sphere's
  // other 2π / π·2); Gauss–Legendre with 64 nodes is exact for these degrees
  // (the odd-m products are polynomials too: (1 − x²)^m times one).
  const int degree = 24;
  const GaussLegendre rule(64);
  std::vector<double> p(harmonic_count(degree));
  std::vector<double> gram(harmonic_count(degree) * (degree + 1), 0.0);
  double worst = 0.0;
  std::vector<std::vector<double>> values;
  for (double x : rule.nodes) {
    normalized_legendre(degree, x, p.data());
    values.push_back(p);
  }
  for (int m = 0; m <= degree; ++m)
    for (int l = m; l <= degree; ++l)
      for (int k = m; k <= degree; ++k) {
        double sum = 0.0;
        for (std::size_t i = 0; i < rule.nodes.size(); ++i)
          sum += 2.0 * kPi * rule.weights[i] * values[i][harmonic_index(degree, l, m)] *
                 values[i][harmonic_index(degree, k, m)];
        worst = std::max(worst, std::abs(sum - (l == k ? 1.0 : 0.0)));
      }
  EXPECT_LT(worst, 1e-12);
}

TEST(SphericalHarmonics, ZonalFunctionsAreScaledLegendrePolynomials) {
  // P̄_l^0(x) = √((2l+1)/4π) P_l(x): P_2 = (3x² − 1)/2 at x = 0.3.
  const int degree = 4;
  std::vector<double> p(harmonic_count(degree));
  normalized_legendre(degree, 0.3, p.data());
  EXPECT_NEAR(p[harmonic_index(degree, 2, 0)], std::sqrt(5.0 / (4.0 * kPi)) * (3 * 0.09 - 1) / 2, 1e-15);
  // P̄_1^1 = √(3/8π) √(1 − x²) (no Condon–Shortley sign).
  EXPECT_NEAR(p[harmonic_index(degree, 1, 1)], std::sqrt(3.0 / (8.0 * kPi)) * std::sqrt(1 - 0.09), 1e-15);
}

TEST(SphericalHarmonics, HenyeyGreensteinMomentsArePowersOfG) {
  for (double g : {0.0, 0.3, 0.76, -0.4, 0.9}) {
    const auto p = phase_legendre_moments([&](double x) { return henyey_greenstein(x, g); }, 40);
    for (int l = 0; l <= 40; ++l) EXPECT_NEAR(p[std::size_t(l)], std::pow(g, l), 1e-10) << "g " << g << " l " << l;
  }
}

TEST(SphericalHarmonics, ClassicRayleighPhaseHasTwoMoments) {
  const auto p = phase_legendre_moments([](double x) { return rayleigh_phase_classic(x); }, 8);
  EXPECT_NEAR(p[0], 1.0, 1e-13);
  EXPECT_NEAR(p[2], 0.1, 1e-13);
  for (int l : {1, 3, 4, 5, 6, 7, 8}) EXPECT_NEAR(p[std::size_t(l)], 0.0, 1e-13) << l;
}

TEST(SphericalHarmonics, HorizonSplitRuleSeparatesGroundAndSky) {
  const double rb = 6360e3;
  for (double r : {rb, rb + 1.0, rb + 8e3, rb + 100e3}) {
    const HorizonSplitRule rule(rb, r, 12);
    const double mu_h = -std::sqrt(std::max(0.0, 1.0 - (rb / r) * (rb / r)));
    ASSERT_EQ(rule.mu.size(), 24u);
    EXPECT_NEAR(std::accumulate(rule.weight.begin(), rule.weight.end(), 0.0), 2.0, 1e-13);
    for (std::size_t j = 0; j < rule.mu.size(); ++j) {
      if (int(j) < rule.ground_nodes) {
        EXPECT_LT(rule.mu[j], mu_h);
      } else {
        EXPECT_GT(rule.mu[j], mu_h);
      }
    }
    // A step at the horizon is integrated exactly: ∫ [μ > μ_h] dμ = 1 − μ_h.
    double sky = 0.0;
    for (std::size_t j = std::size_t(rule.ground_nodes); j < rule.mu.size(); ++j) sky += rule.weight[j];
    EXPECT_NEAR(sky, 1.0 - mu_h, 1e-13);
  }
}

}  // namespace
}  // namespace zenith::atmosphere::lut
