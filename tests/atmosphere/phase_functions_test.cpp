#include "atmosphere/phase_functions.h"

#include <gtest/gtest.h>

#include "tests/atmosphere/test_util.h"

namespace zenith::atmosphere {
namespace {

using test::integrate_over_sphere;

TEST(PhaseFunctions, ClassicRayleighIsNormalized) {
  EXPECT_NEAR(integrate_over_sphere(rayleigh_phase_classic), 1.0, 1e-12);
  // Closed form: 3/(16π)(1 + cos²θ): forward = 2× side scattering.
  EXPECT_NEAR(rayleigh_phase_classic(1.0), 3.0 / (8.0 * kPi), 1e-15);
  EXPECT_NEAR(rayleigh_phase_classic(0.0), 3.0 / (16.0 * kPi), 1e-15);
}

TEST(PhaseFunctions, PenndorfIntegratesTo0_99991) {
  // 0.7629 (1 + 0.932/3) = 0.99991: Penndorf's fitted constants, kept verbatim.
  EXPECT_NEAR(integrate_over_sphere(rayleigh_phase_penndorf), 0.7629 * (1.0 + 0.932 / 3.0), 1e-12);
  EXPECT_NEAR(integrate_over_sphere(rayleigh_phase_penndorf), 0.99991, 5e-6);
}

TEST(PhaseFunctions, DepolarizedRayleighIsNormalizedAndReducesToClassic) {
  for (double delta : {0.0, 0.0279, 0.09, 0.3})
    EXPECT_NEAR(integrate_over_sphere([&](double mu) { return rayleigh_phase_depolarized(mu, delta); }), 1.0, 1e-12);
  for (double mu : {-1.0, -0.3, 0.0, 0.5, 1.0})
    EXPECT_NEAR(rayleigh_phase_depolarized(mu, 0.0), rayleigh_phase_classic(mu), 1e-15);
}

TEST(PhaseFunctions, HenyeyGreensteinIsNormalizedWithMeanCosineG) {
  for (double g : {-0.9, -0.5, 0.0, 0.3, 0.76, 0.9}) {
    EXPECT_NEAR(integrate_over_sphere([&](double mu) { return henyey_greenstein(mu, g); }), 1.0, 1e-9) << g;
    // The asymmetry parameter is the mean cosine: ∫ P cosθ dω = g.
    EXPECT_NEAR(integrate_over_sphere([&](double mu) { return mu * henyey_greenstein(mu, g); }), g, 1e-9) << g;
  }
  EXPECT_NEAR(henyey_greenstein(0.3, 0.0), 1.0 / (4.0 * kPi), 1e-15);
}

TEST(PhaseFunctions, DoubleHenyeyGreensteinIsNormalized) {
  // The printed eq. (16) uses (1 + g1²) in both numerators and would integrate to
  // (1+g1²)/(1−g1²) weighted terms; the corrected form integrates to one.
  struct Case {
    double g1, g2, alpha;
  };
  for (Case c : {Case{0.85, 0.0, 1.0}, Case{0.72, -0.3, 0.93}, Case{0.03, 0.094, 0.743}, Case{0.4, 0.89, 0.04}}) {
    EXPECT_NEAR(integrate_over_sphere([&](double mu) { return double_henyey_greenstein(mu, c.g1, c.g2, c.alpha); }),
                1.0, 1e-9);
    EXPECT_NEAR(
        integrate_over_sphere([&](double mu) { return mu * double_henyey_greenstein(mu, c.g1, c.g2, c.alpha); }),
        c.alpha * c.g1 + (1.0 - c.alpha) * c.g2, 1e-9);
  }
  // α = 1 is a single HG lobe; the second lobe must not depend on g1.
  EXPECT_DOUBLE_EQ(double_henyey_greenstein(0.2, 0.6, -0.4, 1.0), henyey_greenstein(0.2, 0.6));
  EXPECT_DOUBLE_EQ(double_henyey_greenstein(0.2, 0.6, -0.4, 0.0), henyey_greenstein(0.2, -0.4));
}

TEST(PhaseFunctions, CornetteShanksIsNormalizedAndRayleighAtZeroG) {
  for (double g : {0.0, 0.5, 0.8})
    EXPECT_NEAR(integrate_over_sphere([&](double mu) { return cornette_shanks(mu, g); }), 1.0, 1e-9) << g;
  EXPECT_NEAR(cornette_shanks(0.4, 0.0), rayleigh_phase_classic(0.4), 1e-15);
}

}  // namespace
}  // namespace zenith::atmosphere
