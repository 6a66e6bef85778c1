// stress/: horizon directions placed exactly (checked with the reference
// solver's cancellation-free ray geometry and the tables' ray_hits_ground),
// region classification, error statistics, and the determinism of the sampler.
#include <gtest/gtest.h>

#include <cmath>

#include "atmosphere/lut/parameterization.h"
#include "atmosphere/parameters.h"
#include "atmosphere/reference/geometry.h"
#include "core/units.h"
#include "validate/random_atmosphere.h"
#include "validate/stress_geometry.h"
#include "validate/stress_sampler.h"
#include "validate/stress_statistics.h"

namespace zenith::validate {
namespace {

constexpr double kR = 6371e3, kTop = 6471e3;

TEST(StressGeometry, HorizonDirectionsAreOnTheRightSideFrom1mTo40au) {
  // The constructed rays miss the ground above the horizon and hit it below,
  // with the exact impact parameter p, and are tangent (p = R) on it.
  const Vec3 axis = atmosphere::normalize(Vec3{0.3, -0.2, 0.9});
  const Vec3 tangent = tangent_at_azimuth(axis, 1.0);
  for (double altitude : {1.0, 10.0, 1e3, 1e5, 1e7, 1e9, kMaxCameraDistance_m - kR}) {
    const Vec3 camera = (kR + altitude) * axis;
    const double r = kR + altitude;
    const double beta = horizon_nadir_angle_rad(r, kR);
    for (double eps : {1e-6, 1e-4, 1e-2}) {
      if (eps >= beta) continue;  // far away the planet is narrower than ε: −ε would pass the nadir
      const atmosphere::reference::Ray above(camera, horizon_direction(camera, tangent, kR, eps));
      const atmosphere::reference::Ray below(camera, horizon_direction(camera, tangent, kR, -eps));
      // Exactly on the right side: the reference geometry (perigee form) misses / hits the ground.
      EXPECT_FALSE(atmosphere::reference::atmosphere_interval(above, kR, kTop).ends_on_ground)
          << altitude << " " << eps;
      EXPECT_TRUE(atmosphere::reference::atmosphere_interval(below, kR, kTop).ends_on_ground) << altitude << " " << eps;
      // Exactly p = r sin(β ± ε) = R cos ε ± r cos β sin ε (1 m up, ε = 1e-6: p − R = ±3.6 mm).
      for (double e : {eps, -eps}) {
        const double expected = r * std::cos(beta) * std::sin(e) - kR * (1.0 - std::cos(e));
        const atmosphere::reference::Ray ray(camera, horizon_direction(camera, tangent, kR, e));
        EXPECT_NEAR(ray.impact_parameter_m() - kR, expected, 1e-6 * std::abs(expected) + 1e-12 * r)
            << altitude << " " << e;
        EXPECT_NEAR(offset_from_horizon_rad(camera, ray.direction(), kR), e, 1e-9 * eps) << altitude << " " << e;
      }
      if (r <= kTop) {  // the tables' (r, μ) test agrees at 1e-6 rad
        const atmosphere::lut::ShellGeometry g{kR, kTop};
        EXPECT_FALSE(g.ray_hits_ground(r, atmosphere::dot(camera, above.direction()) / r)) << altitude;
        EXPECT_TRUE(g.ray_hits_ground(r, atmosphere::dot(camera, below.direction()) / r)) << altitude;
      }
    }
    // Exactly on the horizon: tangent to the ground to 1e-9 of R (1 m: 6 mm).
    const atmosphere::reference::Ray on(camera, horizon_direction(camera, tangent, kR, 0.0));
    EXPECT_NEAR(on.impact_parameter_m(), kR, 1e-9 * kR) << altitude;
  }
}

TEST(StressGeometry, HorizonNadirAngleKeepsItsPrecisionAtBothEnds) {
  // 1 m up: β = π/2 − √(2h/R) to first order (5.6e-4 rad); 40 au: β = R/r.
  EXPECT_NEAR(0.5 * zenith::core::kPi - horizon_nadir_angle_rad(kR + 1.0, kR), std::sqrt(2.0 / kR), 1e-10);
  const double far = kMaxCameraDistance_m;
  EXPECT_NEAR(horizon_nadir_angle_rad(far, kR) / (kR / far), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(horizon_nadir_angle_rad(kR, kR), 0.5 * zenith::core::kPi);
}

TEST(StressGeometry, RegionsFollowTheirDefinitions) {
  const Vec3 up{0, 0, 1};
  const Vec3 t = tangent_at_azimuth(up, 0.0);
  const Vec3 camera = (kR + 10.0) * up;
  auto sun_at = [&](double zenith_deg) {
    const double z = zenith_deg * zenith::core::kPi / 180.0;
    return std::cos(z) * up + std::sin(z) * t;
  };
  EXPECT_EQ(classify({camera, up, sun_at(30)}, kR, kTop), Region::sky);
  EXPECT_EQ(classify({camera, -up, sun_at(30)}, kR, kTop), Region::ground);
  EXPECT_EQ(classify({camera, horizon_direction(camera, t, kR, 0.017), sun_at(30)}, kR, kTop), Region::horizon);
  EXPECT_EQ(classify({camera, horizon_direction(camera, t, kR, -0.0175), sun_at(30)}, kR, kTop), Region::ground);
  EXPECT_EQ(classify({camera, up, sun_at(95)}, kR, kTop), Region::twilight);
  EXPECT_EQ(classify({camera, up, sun_at(108.5)}, kR, kTop), Region::night);
  EXPECT_EQ(classify({(kTop + 1.0) * up, -up, sun_at(30)}, kR, kTop), Region::space);
  EXPECT_EQ(classify({kTop * up, -up, sun_at(30)}, kR, kTop), Region::ground);  // at the top is inside
}

TEST(StressStatistics, CountsAndQuantiles) {
  ValueHealth h;
  for (double v : {1.0, 0.0, -1e-30, double(NAN), double(INFINITY), -double(INFINITY), 1.5}) h.check(v, true);
  EXPECT_EQ(h.values, 7u);
  EXPECT_EQ(h.nan, 1u);
  EXPECT_EQ(h.inf, 2u);
  EXPECT_EQ(h.negative, 1u);
  EXPECT_EQ(h.above_one, 1u);
  ErrorDistribution d;
  for (int i = 1; i <= 100; ++i) d.add(i, "at " + std::to_string(i));
  EXPECT_EQ(d.median(), 50.0);
  EXPECT_EQ(d.quantile(0.95), 95.0);
  EXPECT_EQ(d.max(), 100.0);
  EXPECT_EQ(d.max_where(), "at 100");
  const double value[2] = {1.1e-6, 0.0}, reference[2] = {1e-6, 1e-9};
  // Channel 0: 0.1e-6 / max(1e-6, 1e-6) = 0.1; channel 1: 1e-9 / 1e-6 = 1e-3.
  EXPECT_NEAR(relative_error(value, reference, 2, 1e-6), 0.1, 1e-12);
  const double nan_value[1] = {NAN}, one[1] = {1.0};
  EXPECT_TRUE(std::isinf(relative_error(nan_value, one, 1, 1e-6)));
}

TEST(StressSampler, SamplesAreDeterministicFiniteAndReachTheCorners) {
  const StressSampler a(kR, kTop, 7, 3), b(kR, kTop, 7, 3);
  int space = 0, near_horizon = 0, twilight = 0, pairs = 0;
  for (std::uint64_t i = 0; i < 20000; ++i) {
    const StressSample s = a.random(i), t = b.random(i);
    ASSERT_EQ(s.configuration.view.x, t.configuration.view.x);
    const Configuration& c = s.configuration;
    ASSERT_NEAR(atmosphere::length(c.view), 1.0, 1e-12) << i;
    ASSERT_NEAR(atmosphere::length(c.sun), 1.0, 1e-12) << i;
    const double r = atmosphere::length(c.camera_m);
    ASSERT_GE(r - kR, 0.999);
    ASSERT_LE(r, kMaxCameraDistance_m * (1.0 + 1e-12));
    space += r > kTop;
    near_horizon += std::abs(offset_from_horizon_rad(c.camera_m, c.view, kR)) <= 1e-6;
    twilight += classify(c, kR, kTop) == Region::twilight;
    pairs += s.horizon_pair.has_value();
  }
  EXPECT_GT(space, 10000);        // log-uniform altitude: ~60% above Earth's 100 km
  EXPECT_GT(near_horizon, 2000);  // within 1e-6 rad of the horizon
  EXPECT_GT(twilight, 2000);
  EXPECT_GT(pairs, 5000);
  EXPECT_EQ(a.sweep().size(), 9u * 9u * 10u * 3u);
}

TEST(RandomAtmosphere, ParameterSetsAreValidAndDeterministic) {
  for (std::uint64_t i = 0; i < 50; ++i) {
    const auto p = random_atmosphere_parameters(11, i);
    EXPECT_EQ(p, random_atmosphere_parameters(11, i));
    EXPECT_NO_THROW(atmosphere::resolve_atmosphere(p, "random")) << p.dump();
  }
}

}  // namespace
}  // namespace zenith::validate
