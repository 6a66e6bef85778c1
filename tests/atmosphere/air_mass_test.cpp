#include "atmosphere/air_mass.h"

#include <gtest/gtest.h>

#include <cmath>

#include "atmosphere/constants.h"
#include "tests/atmosphere/test_util.h"

namespace zenith::atmosphere {
namespace {

TEST(Pickering, KnownValues) {
  test::expect_published_values(pickering_air_mass,
                                {{90.0, 1.0, 1e-6}, {30.0, 1.9932, 5e-5}, {10.0, 5.5807, 5e-5}, {0.0, 38.749, 5e-4}});
}

TEST(Pickering, MonotoneInAltitude) {
  double previous = pickering_air_mass(0.0);
  for (double h = 0.05; h <= 90.0; h += 0.05) {
    const double x = pickering_air_mass(h);
    // Within 0.04° of the zenith the fitted argument passes 90° and X rises by 2e-7.
    if (h < 85.0) {
      EXPECT_LT(x, previous) << h;
    } else if (h < 89.9) {
      EXPECT_LE(x, previous) << h;
    }
    previous = x;
  }
}

class EarthStretch : public ::testing::Test {
 protected:
  static constexpr double R = 6371e3, top = 6471e3, H = 7995.75;
  AirMassStretch stretch = AirMassStretch::pickering(R, top, DensityProfile::exponential(H));
};

TEST_F(EarthStretch, GroundObserverSeesPickeringAirMass) {
  // s · X_geometric = X_Pickering at every elevation, by construction.
  for (double h : {0.0, 0.5, 2.0, 10.0, 30.0, 60.0, 90.0}) {
    const double mu = std::sin(h * kPi / 180.0);
    EXPECT_NEAR(stretch(R, mu) * stretch.geometric_air_mass(h), pickering_air_mass(h), pickering_air_mass(h) * 2e-3)
        << h;
  }
}

TEST_F(EarthStretch, GeometricAirMassOfExponentialAtmosphere) {
  // Zenith: exactly 1. Horizon: Chapman's grazing value √(πR/2H) (1 + H/(8R)...) ≈ 35.4.
  EXPECT_NEAR(stretch.geometric_air_mass(90.0), 1.0, 1e-9);
  EXPECT_NEAR(stretch.geometric_air_mass(0.0), std::sqrt(kPi * R / (2.0 * H)), 0.2);
  // Close to the plane-parallel 1/sin h well above the horizon (curvature lowers it slightly).
  EXPECT_NEAR(stretch.geometric_air_mass(30.0), 2.0, 0.01);
  EXPECT_LT(stretch.geometric_air_mass(30.0), 2.0);
}

TEST_F(EarthStretch, NearOneAtZenithAndAbout1_09AtHorizon) {
  EXPECT_GE(stretch.min_stretch(), 1.0);
  EXPECT_LT(stretch.max_stretch(), 1.12);
  EXPECT_NEAR(stretch(R, 1.0), 1.0, 1e-5);
  EXPECT_GT(stretch(R, 0.0), 1.05);
  EXPECT_LT(stretch(R, 0.0), 1.12);
}

TEST_F(EarthStretch, ConstantAlongAStraightRay) {
  // A ray from the ground at 5° elevation, sampled along its length.
  const double mu0 = std::sin(5.0 * kPi / 180.0);
  const double s0 = stretch(R, mu0);
  for (double d = 1e3; d < 1e6; d *= 2.0) {
    const double r = std::sqrt(R * R + d * d + 2.0 * R * d * mu0);
    const double mu = (R * mu0 + d) / r;
    EXPECT_NEAR(stretch(r, mu), s0, 1e-9) << d;
  }
}

TEST_F(EarthStretch, ContinuousAcrossTheGroundTangentRay) {
  // Rays whose lowest point passes just below and just above the ground.
  const double r = R + 10e3;
  const double mu_tangent = -std::sqrt(1.0 - (R / r) * (R / r));
  const double below = stretch(r, mu_tangent - 1e-9), above = stretch(r, mu_tangent + 1e-9);
  EXPECT_NEAR(below, above, 1e-4);
  // And it fades back to 1 for rays passing far above the atmosphere's dense part.
  EXPECT_NEAR(stretch(top, 0.0), 1.0, 1e-4);
}

TEST(AirMassStretchDisabled, IsIdentity) {
  AirMassStretch none;
  EXPECT_FALSE(none.enabled());
  EXPECT_EQ(none(6371e3, 0.0), 1.0);
}

}  // namespace
}  // namespace zenith::atmosphere
