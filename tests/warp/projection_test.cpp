// warp/ projections: planar asymmetric frusta and the angular fisheye (dome
// master). Round trips, known directions, the dome-master orientation, the
// image circle, parameter errors, the per-pixel angle bound, and the GPU float
// layout evaluated in C++ the way shaders/projection.glsl does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/units.h"
#include "tests/warp/projection_test_support.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"

namespace zenith::warp {
namespace {

using core::kDeg;

using namespace testing;  // the helpers of tests/warp/projection_test_support.h

std::vector<Named> planar_cases() {
  return {
      {"symmetric 90° 64×48", std::make_shared<PlanarProjection>(PlanarProjection::symmetric(64, 48, 90.0))},
      {"asymmetric", std::make_shared<PlanarProjection>(97, 41, PlanarFrustum{-20.0, 45.0, -10.0, 30.0})},
      {"yawed, pitched, rolled",
       std::make_shared<PlanarProjection>(640, 480, PlanarFrustum{-30.0, 25.0, -15.0, 20.0, 35.0, -20.0, 15.0})},
      {"off-axis, all to one side",
       std::make_shared<PlanarProjection>(300, 200, PlanarFrustum{10.0, 40.0, 5.0, 30.0, -100.0, 60.0, -170.0})},
      {"nearly 180° wide", std::make_shared<PlanarProjection>(1920, 1080, PlanarFrustum{-88.5, 88.5, -80.0, 85.0})},
      {"straight up",
       std::make_shared<PlanarProjection>(33, 17, PlanarFrustum{-40.0, 35.0, -25.0, 30.0, 180.0, 90.0, -180.0})},
  };
}

std::vector<Named> fisheye_cases() {
  auto make = [](int w, int h, FisheyeParameters p) { return std::make_shared<FisheyeProjection>(w, h, p); };
  return {
      {"180° 64×64", make(64, 64, {})},
      {"210° 65×65", make(65, 65, {.fov_deg = 210.0})},
      {"360° 64×64", make(64, 64, {.fov_deg = 360.0})},
      {"180° tilted 30° 100×80", make(100, 80, {.tilt_deg = 30.0})},
      {"220° tilted -45° rotated 70°", make(90, 90, {.fov_deg = 220.0, .tilt_deg = -45.0, .rotation_deg = 70.0})},
      {"forward-looking 150°", make(64, 48, {.fov_deg = 150.0, .tilt_deg = 90.0})},
      {"off-centre, cropped 1920×1080", make(1920, 1080,
                                             {.fov_deg = 200.0,
                                              .tilt_deg = 20.0,
                                              .centre_x_px = 960.0,
                                              .centre_y_px = 1000.0,
                                              .radius_px = 1100.0,
                                              .rotation_deg = 15.0})},
      {"8K dome master 180°", make(8192, 8192, {})},
      {"small circle, 1° fov", make(50, 40, {.fov_deg = 1.0, .centre_x_px = 20.0, .radius_px = 10.0})},
  };
}

/// Max round-trip error (px) of pixel(ray(x, y)) over the sample grid; counts
/// the positions that have a ray. Skips positions within `skip_rim_px` of a
/// fisheye's rim (for fov 360 the whole rim is one direction).
double round_trip_error(const Projection& p, int* with_ray, double skip_rim_px = 0.0) {
  const auto* fisheye = dynamic_cast<const FisheyeProjection*>(&p);
  double worst = 0.0;
  for (double y : sample_positions(p.height()))
    for (double x : sample_positions(p.width())) {
      if (fisheye && skip_rim_px > 0.0 &&
          std::abs(std::hypot(x - fisheye->centre_x_px(), y - fisheye->centre_y_px()) - fisheye->radius_px()) <
              skip_rim_px)
        continue;
      const std::optional<glm::dvec3> ray = p.ray(x, y);
      if (!ray) continue;
      ++*with_ray;
      const std::optional<glm::dvec2> back = p.pixel(*ray);
      if (!back) {
        ADD_FAILURE() << p.describe() << ": pixel(ray(" << x << ", " << y << ")) has no pixel";
        continue;
      }
      worst = std::max(worst, std::hypot(back->x - x, back->y - y));
    }
  return worst;
}

TEST(PlanarProjection, RoundTripsOverTheImageIncludingItsEdges) {
  for (const Named& c : planar_cases()) {
    int with_ray = 0;
    const double error = round_trip_error(*c.projection, &with_ray);
    EXPECT_LT(error, 1e-4) << c.name;
    EXPECT_EQ(with_ray, static_cast<int>(sample_positions(c.projection->width()).size() *
                                         sample_positions(c.projection->height()).size()))
        << c.name;  // every position of a plane has a ray
    std::printf("%-28s %-70s round trip max %.3g px\n", c.name.c_str(), c.projection->describe().c_str(), error);
  }
}

TEST(FisheyeProjection, RoundTripsOverTheImageCircleIncludingItsRim) {
  for (const Named& c : fisheye_cases()) {
    const auto& f = dynamic_cast<const FisheyeProjection&>(*c.projection);
    int with_ray = 0;
    // For fov 360 the rim is a single direction: positions on it cannot come back.
    const double error = round_trip_error(f, &with_ray, f.fov_deg() == 360.0 ? 1e-3 : 0.0);
    EXPECT_LT(error, 1e-4) << c.name;
    EXPECT_GT(with_ray, 100) << c.name;
    std::printf("%-30s %-70s round trip max %.3g px\n", c.name.c_str(), f.describe().c_str(), error);
  }
}

TEST(FisheyeProjection, RoundTripsAtTheRimExactly) {
  // Points on the circle itself (r = radius_px) have rays and map back, fov < 360.
  for (double fov : {1.0, 90.0, 180.0, 210.0, 359.0}) {
    const FisheyeProjection f(200, 100, {.fov_deg = fov, .tilt_deg = 10.0, .rotation_deg = 5.0});
    for (int i = 0; i < 64; ++i) {
      const double phi = 2.0 * zenith::core::kPi * i / 64.0;
      const double x = f.centre_x_px() + f.radius_px() * std::cos(phi);
      const double y = f.centre_y_px() + f.radius_px() * std::sin(phi);
      const auto ray = f.ray(x, y);
      if (!ray) continue;  // the rounded point may fall a hair outside
      const auto back = f.pixel(*ray);
      ASSERT_TRUE(back.has_value()) << fov << " " << i;
      EXPECT_LT(std::hypot(back->x - x, back->y - y), 1e-4) << fov << " " << i;
    }
  }
}

TEST(PlanarProjection, SymmetricCentreLooksForwardAndCornersMatchTheFrustum) {
  const PlanarProjection p = PlanarProjection::symmetric(64, 48, 90.0);
  expect_direction(p.ray(32.0, 24.0), {0.0, 0.0, -1.0}, "centre");
  expect_direction(p.ray(64.0, 24.0), {1.0, 0.0, -1.0}, "right edge at 45°");
  expect_direction(p.ray(0.0, 24.0), {-1.0, 0.0, -1.0}, "left edge at -45°");
  expect_direction(p.ray(32.0, 0.0), {0.0, 0.75, -1.0}, "top edge: tan(v/2) = tan(45°) · 48/64");
  EXPECT_NEAR(p.frustum().up_deg, std::atan(0.75) / kDeg, 1e-12);
  EXPECT_NEAR(p.frustum().down_deg, -std::atan(0.75) / kDeg, 1e-12);

  // Corner rays of an asymmetric frustum have the tangents of its angles.
  const PlanarFrustum f{-20.0, 45.0, -10.0, 30.0};
  const PlanarProjection a(97, 41, f);
  struct Corner {
    double x, y, horizontal_deg, vertical_deg;
  };
  for (const Corner& c : {Corner{0, 0, f.left_deg, f.up_deg}, Corner{97, 0, f.right_deg, f.up_deg},
                          Corner{0, 41, f.left_deg, f.down_deg}, Corner{97, 41, f.right_deg, f.down_deg}}) {
    const auto d = a.ray(c.x, c.y);
    ASSERT_TRUE(d);
    EXPECT_NEAR(d->x / -d->z, std::tan(c.horizontal_deg * kDeg), 1e-13) << c.x << ", " << c.y;
    EXPECT_NEAR(d->y / -d->z, std::tan(c.vertical_deg * kDeg), 1e-13) << c.x << ", " << c.y;
  }
  // The axis (tangent 0, 0) lies at the pixel where u and v vanish.
  expect_pixel(a.pixel({0.0, 0.0, -1.0}),
               97.0 * std::tan(20.0 * kDeg) / (std::tan(45.0 * kDeg) + std::tan(20.0 * kDeg)),
               41.0 * std::tan(30.0 * kDeg) / (std::tan(30.0 * kDeg) + std::tan(10.0 * kDeg)), "axis");
}

TEST(PlanarProjection, YawTurnsRightPitchLooksUpRollBanksRight) {
  const PlanarFrustum square{-20.0, 20.0, -20.0, 20.0};
  auto with = [&](double yaw, double pitch, double roll) {
    PlanarFrustum f = square;
    f.yaw_deg = yaw;
    f.pitch_deg = pitch;
    f.roll_deg = roll;
    return PlanarProjection(40, 40, f);
  };
  expect_direction(with(30.0, 0.0, 0.0).ray(20.0, 20.0), {std::sin(30.0 * kDeg), 0.0, -std::cos(30.0 * kDeg)},
                   "yaw 30");
  expect_direction(with(0.0, 20.0, 0.0).ray(20.0, 20.0), {0.0, std::sin(20.0 * kDeg), -std::cos(20.0 * kDeg)},
                   "pitch 20");
  expect_direction(with(90.0, 0.0, 0.0).ray(20.0, 20.0), {1.0, 0.0, 0.0}, "yaw 90 looks right");
  expect_direction(with(0.0, 90.0, 0.0).ray(20.0, 20.0), {0.0, 1.0, 0.0}, "pitch 90 looks up");
  const double yaw = 50.0 * kDeg, pitch = -25.0 * kDeg;
  expect_direction(with(50.0, -25.0, 33.0).ray(20.0, 20.0),
                   {std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)},
                   "axis of yaw 50 pitch -25 (roll does not move it)");
  // Roll 90 banks right: the frustum's up (the top-centre pixel) turns to +x.
  const double t = std::tan(20.0 * kDeg);
  expect_direction(with(0.0, 0.0, 90.0).ray(20.0, 0.0), {t, 0.0, -1.0}, "roll 90: top-centre looks right");
  expect_direction(with(0.0, 0.0, 90.0).ray(40.0, 20.0), {0.0, -t, -1.0}, "roll 90: right-centre looks down");
  // Order: roll about the frustum's own axis, then pitch, then yaw. Pitched up
  // 90°, the frustum's top edge lies toward +z (backward), its right edge +x.
  expect_direction(with(0.0, 90.0, 0.0).ray(20.0, 0.0), {0.0, 1.0, t}, "pitch 90: top-centre leans backward");
  expect_direction(with(0.0, 90.0, 0.0).ray(40.0, 20.0), {t, 1.0, 0.0}, "pitch 90: right-centre leans right");
}

TEST(PlanarProjection, DirectionsBehindThePlaneHaveNoPixel) {
  const PlanarProjection p(64, 48, PlanarFrustum{-30.0, 30.0, -20.0, 20.0, 90.0, 0.0, 0.0});  // looks along +x
  EXPECT_FALSE(p.pixel({-1.0, 0.0, 0.0}));
  EXPECT_FALSE(p.pixel({-1e-9, 0.0, -1.0}));  // a hair more than 90° from the axis
  EXPECT_FALSE(p.pixel({0.0, 0.0, 0.0}));
  EXPECT_FALSE(p.pixel({std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}));
  EXPECT_FALSE(p.ray(std::numeric_limits<double>::infinity(), 1.0));
  expect_pixel(p.pixel({5.0, 0.0, 0.0}), 32.0, 24.0, "axis, not unit");
  // Outside the frustum but in front: a position outside the image, as it is.
  const auto outside = p.pixel({1.0, 0.0, 1.0});  // 45° to the right of +x: beyond right_deg = 30
  ASSERT_TRUE(outside);
  EXPECT_GT(outside->x, 64.0);
}

TEST(FisheyeProjection, DomeMasterOrientation) {
  const FisheyeProjection f(64, 64);  // fov 180, centre (32, 32), radius 32
  expect_direction(f.ray(32.0, 32.0), {0.0, 1.0, 0.0}, "centre = up (zenith)");
  expect_direction(f.ray(32.0, 64.0), {0.0, 0.0, -1.0}, "bottom-centre = forward horizon");
  expect_direction(f.ray(32.0, 0.0), {0.0, 0.0, 1.0}, "top-centre = backward horizon");
  expect_direction(f.ray(64.0, 32.0), {1.0, 0.0, 0.0}, "right = +x");
  expect_direction(f.ray(0.0, 32.0), {-1.0, 0.0, 0.0}, "left = -x");
  expect_direction(f.ray(32.0, 48.0), {0.0, 1.0, -1.0}, "halfway down: 45° above the forward horizon");
  expect_pixel(f.pixel({0.0, 0.0, -1.0}), 32.0, 64.0, "forward");
  expect_pixel(f.pixel({1.0, 1.0, 0.0}), 32.0 + 16.0, 32.0, "45° toward the right");
  EXPECT_FALSE(f.pixel({0.0, -1.0, 0.0})) << "below the horizon of a 180° dome";
  EXPECT_FALSE(f.pixel({0.0, -1e-9, -1.0})) << "a hair below the horizon";
  EXPECT_EQ(f.describe(), "fisheye 180° 64×64");
}

TEST(FisheyeProjection, TiltTurnsTheAxisTowardForwardAndRotationSpinsThePicture) {
  const FisheyeProjection t30(64, 64, {.tilt_deg = 30.0});
  expect_direction(t30.ray(32.0, 32.0), {0.0, std::cos(30.0 * kDeg), -std::sin(30.0 * kDeg)}, "tilt 30 centre");
  expect_direction(t30.ray(64.0, 32.0), {1.0, 0.0, 0.0}, "tilt 30 right stays +x");
  expect_direction(t30.ray(32.0, 0.0), {0.0, std::sin(30.0 * kDeg), std::cos(30.0 * kDeg)}, "tilt 30 top");

  const FisheyeProjection t90(64, 64, {.tilt_deg = 90.0});
  expect_direction(t90.ray(32.0, 32.0), {0.0, 0.0, -1.0}, "tilt 90 looks forward");
  expect_direction(t90.ray(32.0, 0.0), {0.0, 1.0, 0.0}, "tilt 90: sky at the top");
  expect_direction(t90.ray(64.0, 32.0), {1.0, 0.0, 0.0}, "tilt 90: right is right");

  const FisheyeProjection r90(64, 64, {.rotation_deg = 90.0});
  expect_direction(r90.ray(64.0, 32.0), {0.0, 0.0, -1.0}, "rotation 90: forward at the right");
  expect_direction(r90.ray(32.0, 0.0), {1.0, 0.0, 0.0}, "rotation 90: +x at the top");
  expect_direction(r90.ray(32.0, 32.0), {0.0, 1.0, 0.0}, "rotation keeps the axis");

  EXPECT_EQ(t30.describe(), "fisheye 180° 64×64, tilt 30°");
  EXPECT_EQ(FisheyeProjection(100, 80, {.fov_deg = 210.0, .radius_px = 50.0}).describe(),
            "fisheye 210° 100×80, circle r=50 px at (50, 40)");
}

TEST(FisheyeProjection, WideFieldsOfView) {
  const FisheyeProjection f210(64, 64, {.fov_deg = 210.0});
  expect_direction(f210.ray(32.0, 64.0), {0.0, -std::sin(15.0 * kDeg), -std::cos(15.0 * kDeg)},
                   "210°: the bottom of the rim is 15° below the forward horizon");
  expect_pixel(f210.pixel({0.0, 0.0, -1.0}), 32.0, 32.0 + 32.0 * 90.0 / 105.0, "210°: forward horizon");

  const FisheyeProjection f360(64, 64, {.fov_deg = 360.0});
  expect_direction(f360.ray(32.0, 48.0), {0.0, 0.0, -1.0}, "360°: half the radius down is forward");
  expect_direction(f360.ray(32.0, 64.0), {0.0, -1.0, 0.0}, "360°: the rim is the direction opposite the axis");
  expect_direction(f360.ray(0.0, 32.0), {0.0, -1.0, 0.0}, "360°: every rim point");
  expect_direction(f360.ray(32.0 + 32.0 * std::cos(1.0), 32.0 + 32.0 * std::sin(1.0)), {0.0, -1.0, 0.0},
                   "360°: every rim point (at 1 rad)");
  expect_pixel(f360.pixel({0.0, -1.0, 0.0}), 32.0, 64.0, "360°: the nadir maps to the rim below the centre");
  expect_pixel(f360.pixel({0.0, -1.0, -1e-300}), 32.0, 64.0, "360°: a hair off the nadir");
  // Every direction of the sphere has a pixel.
  for (int i = 0; i < 200; ++i) {
    const double z = -1.0 + (i + 0.5) / 100.0, phi = 2.399963 * i;  // golden-angle spiral
    const glm::dvec3 d(std::sqrt(1.0 - z * z) * std::cos(phi), z, std::sqrt(1.0 - z * z) * std::sin(phi));
    const auto px = f360.pixel(d);
    ASSERT_TRUE(px) << i;
    EXPECT_LE(std::hypot(px->x - 32.0, px->y - 32.0), 32.0 + 1e-9) << i;
    expect_direction(f360.ray(px->x, px->y), d, "sphere point " + std::to_string(i));
  }
}

TEST(FisheyeProjection, PixelsOutsideTheCircleHaveNoRay) {
  const FisheyeProjection f(64, 48);  // radius 24 about (32, 24)
  EXPECT_FALSE(f.ray(0.5, 0.5)) << "corner";
  EXPECT_FALSE(f.ray(63.5, 47.5)) << "corner";
  EXPECT_FALSE(f.ray(2.0, 24.0)) << "left of the circle on a wide image";
  EXPECT_FALSE(f.ray(32.0, 48.0 + 1e-9)) << "a hair below the rim";
  EXPECT_FALSE(f.ray(32.0 + 24.0 + 1e-9, 24.0)) << "a hair right of the rim";
  EXPECT_TRUE(f.ray(32.0, 48.0)) << "on the rim";
  EXPECT_TRUE(f.ray(32.0 + 24.0 * std::cos(0.3) * (1.0 - 1e-12), 24.0 + 24.0 * std::sin(0.3) * (1.0 - 1e-12)));
  EXPECT_FALSE(f.ray(std::numeric_limits<double>::quiet_NaN(), 24.0));
  // Counting: pixel centres with a ray ≈ the circle's area.
  int with_ray = 0;
  for (int j = 0; j < 48; ++j)
    for (int i = 0; i < 64; ++i) with_ray += f.ray(i + 0.5, j + 0.5).has_value();
  EXPECT_NEAR(with_ray, zenith::core::kPi * 24.0 * 24.0, 40.0);

  // A cropped dome master: the circle runs past the image; its centre may lie outside.
  const FisheyeProjection cropped(100, 50, {.centre_x_px = 50.0, .centre_y_px = 70.0, .radius_px = 60.0});
  expect_direction(cropped.ray(50.0, 70.0), {0.0, 1.0, 0.0}, "cropped: zenith at the off-image centre");
  EXPECT_TRUE(cropped.ray(50.5, 10.5));
  EXPECT_FALSE(cropped.ray(0.5, 0.5));
  expect_pixel(cropped.pixel({0.0, 0.0, 1.0}), 50.0, 10.0, "cropped: backward horizon at the top");
  expect_pixel(cropped.pixel({0.0, 0.0, -1.0}), 50.0, 130.0, "cropped: forward horizon off the image, as it is");
}

TEST(PlanarProjection, InvalidParametersThrowNamingThem) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto planar = [](int w, int h, PlanarFrustum f) { return [=] { PlanarProjection(w, h, f); }; };
  expect_invalid(planar(0, 10, {-30, 30, -20, 20}), {"width_px", "0", "[1, 65536]"});
  expect_invalid(planar(10, 65537, {-30, 30, -20, 20}), {"height_px", "65537"});
  expect_invalid(planar(10, 10, {-90, 30, -20, 20}), {"left_deg", "-90", "(-89, 89)", "degrees"});
  expect_invalid(planar(10, 10, {-30, 89, -20, 20}), {"right_deg", "89"});
  expect_invalid(planar(10, 10, {-30, 30, -89.5, 20}), {"down_deg", "-89.5"});
  expect_invalid(planar(10, 10, {-30, 30, -20, nan}), {"up_deg", "nan"});
  expect_invalid(planar(10, 10, {30, 10, -20, 20}), {"left_deg", "right_deg", "less"});
  expect_invalid(planar(10, 10, {-30, 30, 20, 20}), {"down_deg", "up_deg"});
  expect_invalid(planar(10, 10, {-30, 30, -20, 20, 361.0}), {"yaw_deg", "361", "[-360, 360]"});
  expect_invalid(planar(10, 10, {-30, 30, -20, 20, 0.0, -400.0}), {"pitch_deg", "-400", "[-360, 360]"});
  expect_invalid(planar(10, 10, {-30, 30, -20, 20, 0.0, 0.0, nan}), {"roll_deg"});
  expect_invalid([] { PlanarProjection::symmetric(10, 10, 0.0); }, {"horizontal_fov_deg", "0", "(0, 178)"});
  expect_invalid([] { PlanarProjection::symmetric(10, 10, 179.0); }, {"horizontal_fov_deg", "179"});
  expect_invalid([] { PlanarProjection::symmetric(1, 1000, 170.0); }, {"horizontal_fov_deg", "vertical"});
  expect_invalid([] { PlanarProjection::symmetric(-1, 10, 60.0); }, {"width_px", "-1"});
  EXPECT_NO_THROW(PlanarProjection::symmetric(1, 1, 177.9));
  EXPECT_NO_THROW(PlanarProjection(65536, 1, PlanarFrustum{-88.9, 88.9, -1e-3, 1e-3, -180, 90, 180}));
}

TEST(FisheyeProjection, InvalidParametersThrowNamingThem) {
  const double inf = std::numeric_limits<double>::infinity();
  auto fisheye = [](int w, int h, FisheyeParameters p) { return [=] { FisheyeProjection(w, h, p); }; };
  expect_invalid(fisheye(64, 0, {}), {"height_px", "0"});
  expect_invalid(fisheye(70000, 64, {}), {"width_px", "70000"});
  expect_invalid(fisheye(64, 64, {.fov_deg = 0.5}), {"fov_deg", "0.5", "[1, 360]", "degrees"});
  expect_invalid(fisheye(64, 64, {.fov_deg = 361.0}), {"fov_deg", "361"});
  expect_invalid(fisheye(64, 64, {.tilt_deg = 91.0}), {"tilt_deg", "91", "[-90, 90]", "[270, 360]"});
  expect_invalid(fisheye(64, 64, {.tilt_deg = 269.0}), {"tilt_deg", "269", "[-90, 90]"});
  expect_invalid(fisheye(64, 64, {.tilt_deg = 361.0}), {"tilt_deg", "361", "[-360, 360]"});
  expect_invalid(fisheye(64, 64, {.centre_x_px = inf}), {"centre_x_px", "inf", "px"});
  expect_invalid(fisheye(64, 64, {.centre_y_px = -2e6}), {"centre_y_px", "-2e+06"});
  expect_invalid(fisheye(64, 64, {.radius_px = 0.0}), {"radius_px", "0", "(0, 1e+06]", "px"});
  expect_invalid(fisheye(64, 64, {.radius_px = -3.0}), {"radius_px", "-3"});
  expect_invalid(fisheye(64, 64, {.rotation_deg = std::numeric_limits<double>::quiet_NaN()}), {"rotation_deg", "nan"});
  EXPECT_NO_THROW(FisheyeProjection(1, 1, {.fov_deg = 360.0, .tilt_deg = -90.0, .rotation_deg = -360.0}));
}

TEST(Projection, MaxPixelAngleBoundsNeighbouringRays) {
  std::vector<Named> all = planar_cases();
  for (Named& c : fisheye_cases())
    if (c.projection->width() * c.projection->height() < 200000) all.push_back(std::move(c));
  expect_tight_pixel_angle_bounds(all);
}

TEST(Projection, GpuLayoutReproducesTheRaysInFloat) {
  std::vector<Named> all = planar_cases();
  for (Named& c : fisheye_cases()) all.push_back(std::move(c));
  for (const Named& c : all) {
    const Projection& p = *c.projection;
    const GpuProjection g = p.gpu();
    EXPECT_EQ(g.kind, dynamic_cast<const FisheyeProjection*>(&p) ? ProjectionKind::fisheye : ProjectionKind::planar);
    const auto* fisheye = dynamic_cast<const FisheyeProjection*>(&p);
    double worst = 0.0;
    const int step_x = std::max(1, p.width() / 64), step_y = std::max(1, p.height() / 64);
    for (int j = 0; j < p.height(); j += step_y)
      for (int i = 0; i < p.width(); i += step_x) {
        const double x = i + 0.5, y = j + 0.5;
        const auto cpu = p.ray(x, y);
        const auto gpu = emulate_glsl(g, glm::vec2(static_cast<float>(x), static_cast<float>(y)));
        if (cpu && gpu) {
          worst = std::max(worst, angle_between(*cpu, glm::dvec3(*gpu)));
        } else if (cpu.has_value() != gpu.has_value()) {
          ASSERT_TRUE(fisheye) << c.name;
          EXPECT_LT(std::abs(std::hypot(x - fisheye->centre_x_px(), y - fisheye->centre_y_px()) - fisheye->radius_px()),
                    1e-4)
              << c.name << " pixel " << i << ", " << j;
        }
      }
    EXPECT_LT(worst, 2e-6) << c.name;
    std::printf("%-30s float emulation of projection.glsl: max %.3g rad\n", c.name.c_str(), worst);
  }
}

}  // namespace
}  // namespace zenith::warp
