// Twinkling in the star pass (render/night/star_placement.h, astro/scintillation.h):
// on the CPU, without GL — two synthetic stars, one at the zenith and one 10°
// above the horizon, placed with and without scintillation. Each twinkling
// splat is the steady one times the log-normal factor of its own air mass and
// draw; the mean over many intervals keeps the flux.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "astro/scintillation.h"
#include "atmosphere/air_mass.h"
#include "render/night/star_placement.h"
#include "warp/fisheye_projection.h"

namespace zenith::render {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct TwoStars {
  warp::FisheyeProjection projection{96, 96};
  StarField field;
  std::vector<glm::dvec3> directions;
  StarFrame frame;

  static astro::StarCatalogue catalogue() {
    astro::StarCatalogue c;
    c.magnitude_limit = 7.0;
    c.stars.resize(2);
    c.stars[0].v_mag = 1.0;  // at the zenith
    c.stars[1].v_mag = 1.0;  // 10° above the northern horizon
    c.stars[1].b_minus_v = 0.6;
    return c;
  }

  TwoStars() : field(catalogue(), {440.0, 550.0, 680.0}) {
    directions = {{0.0, 0.0, 1.0}, {0.0, std::cos(10.0 * kDeg), std::sin(10.0 * kDeg)}};
    frame.projection = &projection;
    // The camera looks at the zenith: the fisheye's centre ray is the world's up.
    const glm::dvec3 up(0.0, 0.0, 1.0), centre = glm::normalize(*projection.ray(48.0, 48.0));
    const glm::dvec3 axis = glm::cross(up, centre);
    if (glm::length(axis) > 1e-12)
      frame.world_to_camera =
          glm::mat3_cast(glm::angleAxis(std::acos(std::clamp(glm::dot(up, centre), -1.0, 1.0)), glm::normalize(axis)));
    else if (glm::dot(up, centre) < 0.0)
      frame.world_to_camera = glm::dmat3(1, 0, 0, 0, -1, 0, 0, 0, -1);  // half a turn about x
    frame.rgb_weights = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  }
};

TEST(StarScintillation, EachSplatIsTheSteadyOneTimesItsOwnFactor) {
  TwoStars s;
  const std::vector<StarSplat> steady = star_splats(s.field, s.directions, s.frame);
  ASSERT_EQ(steady.size(), 2u);
  const astro::ScintillationOptions eye;
  s.frame.set_twinkling(eye, 17739521, 0.0, astro::kEarthGroundRefractivity550);
  const std::vector<StarSplat> twinkling = star_splats(s.field, s.directions, s.frame);
  ASSERT_EQ(twinkling.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const StarSplat& a = steady[k];
    const StarSplat& b = twinkling[k];
    ASSERT_FLOAT_EQ(a.x_px, b.x_px);
    ASSERT_FLOAT_EQ(a.y_px, b.y_px);
    // Which star: the zenith one lands at the image's centre.
    const bool zenith = std::abs(a.x_px - 48.0f) < 1.0f && std::abs(a.y_px - 48.0f) < 1.0f;
    const std::uint64_t star = zenith ? 0 : 1;
    const double air_mass = atmosphere::pickering_air_mass(zenith ? 90.0 : 10.0);
    const double variance = astro::scintillation_variance(eye, air_mass, 0.0, astro::kEarthGroundRefractivity550);
    const double factor = astro::scintillation_factor(variance, astro::scintillation_normal(star, 17739521));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(b.rgb[c] / a.rgb[c], factor, 2e-6 * factor) << k << ' ' << c;
  }
}

TEST(StarScintillation, TheLowStarTwinklesMoreAndBothKeepTheirMeanFlux) {
  TwoStars s;
  const std::vector<StarSplat> steady = star_splats(s.field, s.directions, s.frame);
  const astro::ScintillationOptions eye;
  s.frame.set_twinkling(eye, 0, 0.0, astro::kEarthGroundRefractivity550);
  constexpr int kIntervals = 4000;
  double sum[2] = {0, 0}, log_sum[2] = {0, 0}, log_sum2[2] = {0, 0};
  for (int t = 0; t < kIntervals; ++t) {
    s.frame.scintillation_interval = t;
    const std::vector<StarSplat> now = star_splats(s.field, s.directions, s.frame);
    ASSERT_EQ(now.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      const double ratio = double(now[k].rgb[1]) / double(steady[k].rgb[1]);
      sum[k] += ratio;
      log_sum[k] += std::log(ratio);
      log_sum2[k] += std::log(ratio) * std::log(ratio);
    }
  }
  // The factor is log-normal: ln f has variance s² = ln(1 + σ_I²), estimated
  // within 5 standard errors (s² √(2/n)); the mean of f is 1 within 5 of its.
  const bool first_is_zenith = std::abs(steady[0].x_px - 48.0f) < 1.0f && std::abs(steady[0].y_px - 48.0f) < 1.0f;
  for (int k = 0; k < 2; ++k) {
    const bool zenith = (k == 0) == first_is_zenith;
    const double sigma2 = zenith ? 0.0072213 : 1.0;  // 10° up (X = 5.58) it saturates
    const double s2 = std::log1p(sigma2);
    const double log_mean = log_sum[k] / kIntervals;
    const double log_variance = log_sum2[k] / kIntervals - log_mean * log_mean;
    EXPECT_NEAR(log_variance, s2, 5.0 * s2 * std::sqrt(2.0 / kIntervals)) << (zenith ? "zenith" : "10 deg");
    const double mean = sum[k] / kIntervals;
    EXPECT_NEAR(mean, 1.0, 5.0 * std::sqrt(sigma2 / kIntervals)) << (zenith ? "zenith" : "10 deg");
  }
}

}  // namespace
}  // namespace zenith::render
