// warp/ projections beyond planar and fisheye: cylindrical panoramas,
// equirectangular (longitude/latitude) images and cube-map faces, and the JSON
// factory. Round trips, known directions, the 360° seams, the cube's faces
// covering the sphere once in OpenGL's orientation, parameter errors, the
// per-pixel angle bound and the GPU float layout evaluated in C++ the way
// shaders/projection.glsl does (tests/render/projection_gpu_test.cpp runs the shader).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/json_reader.h"
#include "core/units.h"
#include "tests/warp/projection_test_support.h"
#include "warp/cube_face_projection.h"
#include "warp/cylindrical_projection.h"
#include "warp/equirectangular_projection.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"
#include "warp/projection_factory.h"

namespace zenith::warp {
namespace {

using core::kDeg;
using core::kPi;

using namespace testing;  // the helpers of tests/warp/projection_test_support.h

/// Uniform random unit vectors (fixed seed).
std::vector<glm::dvec3> random_directions(int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<glm::dvec3> out;
  while (static_cast<int>(out.size()) < count) {
    const glm::dvec3 v(normal(rng), normal(rng), normal(rng));
    if (glm::length(v) > 1e-6) out.push_back(glm::normalize(v));
  }
  return out;
}

std::vector<Named> cylindrical_cases() {
  auto make = [](int w, int h, CylindricalParameters p) { return std::make_shared<CylindricalProjection>(w, h, p); };
  return {
      {"360° ±45° 256×64", make(256, 64, {})},
      {"360° asymmetric 101×37", make(101, 37, {.horizontal_fov_deg = 360.0, .down_deg = -20.0, .up_deg = 60.0})},
      {"180° wall 320×90", make(320, 90, {.horizontal_fov_deg = 180.0, .down_deg = -15.0, .up_deg = 25.0})},
      {"120° above the horizon", make(200, 50, {.horizontal_fov_deg = 120.0, .down_deg = 10.0, .up_deg = 80.0})},
      {"270° turned", make(300, 80,
                           {.horizontal_fov_deg = 270.0,
                            .down_deg = -30.0,
                            .up_deg = 40.0,
                            .yaw_deg = 35.0,
                            .pitch_deg = -20.0,
                            .roll_deg = 15.0})},
      {"10° sliver, near 89°", make(40, 300, {.horizontal_fov_deg = 10.0, .down_deg = -88.9, .up_deg = 88.9})},
      {"360° straight up",
       make(128, 64, {.down_deg = -60.0, .up_deg = 60.0, .yaw_deg = 180.0, .pitch_deg = 90.0, .roll_deg = -180.0})},
  };
}

std::vector<Named> equirectangular_cases() {
  auto make = [](int w, int h, EquirectangularParameters p) {
    return std::make_shared<EquirectangularProjection>(w, h, p);
  };
  return {
      {"360°×180° 256×128", make(256, 128, {})},
      {"360°×180° odd 101×37", make(101, 37, {})},
      {"front half 180°×90°", make(160, 80, {-90.0, 90.0, -45.0, 45.0})},
      {"behind, over the seam", make(120, 50, {120.0, 240.0, -10.0, 60.0})},
      {"sky cap", make(200, 30, {-180.0, 180.0, 60.0, 90.0})},
      {"360° from 0°", make(90, 45, {0.0, 360.0, -90.0, 90.0})},
      {"narrow strip", make(30, 200, {-5.0, 5.0, -80.0, 85.0})},
  };
}

std::vector<Named> cube_cases() {
  std::vector<Named> out;
  for (int f = 0; f < 6; ++f)
    for (int size : {1, 64, 65}) {
      auto p = std::make_shared<CubeFaceProjection>(size, static_cast<CubeFace>(f));
      out.push_back({p->describe(), p});
    }
  return out;
}

std::vector<Named> all_cases() {
  std::vector<Named> all = cylindrical_cases();
  for (Named& c : equirectangular_cases()) all.push_back(std::move(c));
  for (Named& c : cube_cases()) all.push_back(std::move(c));
  return all;
}

/// Whether x = 0 and x = width are one column of rays (a 360° cylinder or range).
bool wraps(const Projection& p) {
  if (const auto* c = dynamic_cast<const CylindricalProjection*>(&p))
    return c->parameters().horizontal_fov_deg == 360.0;
  if (const auto* e = dynamic_cast<const EquirectangularProjection*>(&p))
    return e->parameters().longitude_max_deg - e->parameters().longitude_min_deg == 360.0;
  return false;
}

/// Max round-trip error (px) of pixel(ray(x, y)) over the sample grid; x is
/// compared modulo the width where the image wraps around.
double round_trip_error(const Projection& p, int* with_ray) {
  const bool wrap = wraps(p);
  double worst = 0.0;
  for (double y : sample_positions(p.height()))
    for (double x : sample_positions(p.width())) {
      const std::optional<glm::dvec3> ray = p.ray(x, y);
      if (!ray) {
        ADD_FAILURE() << p.describe() << ": no ray at " << x << ", " << y;
        continue;
      }
      ++*with_ray;
      const std::optional<glm::dvec2> back = p.pixel(*ray);
      if (!back) {
        ADD_FAILURE() << p.describe() << ": pixel(ray(" << x << ", " << y << ")) has no pixel";
        continue;
      }
      double dx = std::abs(back->x - x);
      if (wrap) {
        dx = std::min(dx, std::abs(dx - p.width()));
        EXPECT_GE(back->x, 0.0) << p.describe();
        EXPECT_LT(back->x, p.width()) << p.describe();
      }
      worst = std::max(worst, std::hypot(dx, back->y - y));
    }
  return worst;
}

TEST(MoreProjections, RoundTripOverTheImageIncludingItsEdges) {
  for (const Named& c : all_cases()) {
    int with_ray = 0;
    const double error = round_trip_error(*c.projection, &with_ray);
    EXPECT_LT(error, 1e-4) << c.name;
    EXPECT_GT(with_ray, 100) << c.name;
    std::printf("%-28s %-72s round trip max %.3g px\n", c.name.c_str(), c.projection->describe().c_str(), error);
  }
}

TEST(MoreProjections, DirectionsRoundTripThroughPixels) {
  // ray(pixel(d)) == d for every direction a projection sees (here: random
  // directions whose pixel lies within one image of the rectangle).
  for (const Named& c : all_cases()) {
    const Projection& p = *c.projection;
    double worst = 0.0;
    int seen = 0;
    for (const glm::dvec3& d : random_directions(2000, 7)) {
      const auto px = p.pixel(d);
      if (!px || std::abs(px->x - 0.5 * p.width()) > p.width() || std::abs(px->y - 0.5 * p.height()) > p.height())
        continue;
      const auto back = p.ray(px->x, px->y);
      ASSERT_TRUE(back) << c.name;
      worst = std::max(worst, angle_between(*back, d));
      ++seen;
    }
    EXPECT_GT(seen, 50) << c.name;
    EXPECT_LT(worst, 1e-12) << c.name;
  }
}

TEST(CylindricalProjection, CentreLooksForwardAndEdgesLieAtTheFieldOfView) {
  const CylindricalProjection c(320, 90, {.horizontal_fov_deg = 180.0, .down_deg = -15.0, .up_deg = 25.0});
  const double horizon_y = 90.0 * std::tan(25.0 * kDeg) / (std::tan(25.0 * kDeg) + std::tan(15.0 * kDeg));
  expect_direction(c.ray(160.0, horizon_y), {0.0, 0.0, -1.0}, "centre column on the horizon = forward");
  expect_direction(c.ray(0.0, horizon_y), {-1.0, 0.0, 0.0}, "left edge: 90° left");
  expect_direction(c.ray(320.0, horizon_y), {1.0, 0.0, 0.0}, "right edge: 90° right");
  expect_direction(c.ray(240.0, horizon_y), {1.0, 0.0, -1.0}, "three quarters: 45° right");
  expect_direction(c.ray(160.0, 0.0), {0.0, std::tan(25.0 * kDeg), -1.0}, "top edge 25° up");
  expect_direction(c.ray(160.0, 90.0), {0.0, -std::tan(15.0 * kDeg), -1.0}, "bottom edge 15° down");
  expect_direction(c.ray(320.0, 0.0), {1.0, std::tan(25.0 * kDeg), 0.0}, "top-right corner: 25° up, 90° right");
  expect_pixel(c.pixel({0.0, 0.0, -1.0}), 160.0, horizon_y, "forward");
  expect_pixel(c.pixel({0.0, 0.0, 1.0}), 160.0 + 320.0, horizon_y, "backward: beyond the 180° image, as it is");
  // Perspective along verticals: a column's rays keep their azimuth.
  for (double y : {0.0, 20.0, 45.5, 90.0}) {
    const auto d = c.ray(200.0, y);
    ASSERT_TRUE(d);
    EXPECT_NEAR(std::atan2(d->x, -d->z), 40.0 / 320.0 * kPi, 1e-14) << y;
  }
  // v is linear in y: the tangent of the elevation at y = 45 is halfway.
  const auto mid = c.ray(160.0, 45.0);
  ASSERT_TRUE(mid);
  EXPECT_NEAR(mid->y / -mid->z, 0.5 * (std::tan(25.0 * kDeg) - std::tan(15.0 * kDeg)), 1e-14);
  EXPECT_FALSE(c.pixel({0.0, 1.0, 0.0})) << "the cylinder's pole";
  EXPECT_FALSE(c.pixel({0.0, 0.0, 0.0}));
  EXPECT_FALSE(c.ray(320.0 + 160.0 + 1e-9, 10.0)) << "beyond half a turn";
  EXPECT_TRUE(c.ray(320.0 + 160.0, 10.0)) << "exactly half a turn";
  EXPECT_EQ(c.describe(), "cylindrical 180°×40° (down -15° up 25°) 320×90");
}

TEST(CylindricalProjection, YawPitchRollFollowPlanarFrustum) {
  const CylindricalParameters turned{.horizontal_fov_deg = 90.0,
                                     .down_deg = -20.0,
                                     .up_deg = 20.0,
                                     .yaw_deg = 50.0,
                                     .pitch_deg = -25.0,
                                     .roll_deg = 33.0};
  const CylindricalProjection c(60, 40, turned);
  const PlanarProjection p(60, 40, PlanarFrustum{-45.0, 45.0, -20.0, 20.0, 50.0, -25.0, 33.0});
  // The centre ray and the centre column (a vertical line: the same in both) agree.
  for (double y : {0.0, 7.0, 20.0, 40.0}) {
    const auto a = c.ray(30.0, y), b = p.ray(30.0, y);
    ASSERT_TRUE(a && b);
    EXPECT_LT(angle_between(*a, *b), 1e-12) << y;
  }
  expect_direction(CylindricalProjection(60, 40, {.yaw_deg = 90.0}).ray(30.0, 20.0), {1.0, 0.0, 0.0},
                   "yaw 90 looks right");
  expect_direction(CylindricalProjection(60, 40, {.pitch_deg = 90.0}).ray(30.0, 20.0), {0.0, 1.0, 0.0},
                   "pitch 90 looks up");
  EXPECT_EQ(c.describe(), "cylindrical 90°×40° (down -20° up 20°) 60×40, yaw 50° pitch -25° roll 33°");
}

TEST(CylindricalProjection, The360SeamHasNeighbouringRaysOnBothSides) {
  const CylindricalProjection c(256, 64, {.down_deg = -20.0, .up_deg = 60.0});
  const double bound = c.max_pixel_angle_rad();
  for (double y : {0.5, 10.5, 40.5, 63.5}) {
    expect_direction(c.ray(0.0, y), *c.ray(256.0, y), "x = 0 and x = width are one column");
    const auto left = c.ray(0.5, y), right = c.ray(255.5, y);
    ASSERT_TRUE(left && right);
    const double across = angle_between(*left, *right);
    EXPECT_LE(across, bound) << y;                                                       // within one pixel angle
    EXPECT_NEAR(across, angle_between(*c.ray(100.5, y), *c.ray(101.5, y)), 1e-12) << y;  // as any neighbours
    EXPECT_GT(left->z, 0.0) << "both sides look backward";
    EXPECT_LT(left->x, 0.0) << "the left edge turns left of backward";
    EXPECT_GT(right->x, 0.0);
  }
  // Directions a hair either side of straight backward land at the two edges.
  const auto just_left = c.pixel({-1e-9, 0.0, 1.0}), just_right = c.pixel({1e-9, 0.0, 1.0});
  ASSERT_TRUE(just_left && just_right);
  EXPECT_NEAR(just_left->x, 0.0, 1e-6);
  EXPECT_NEAR(just_right->x, 256.0, 1e-6);
  EXPECT_LT(just_right->x, 256.0);
  const auto behind = c.pixel({0.0, 0.0, 1.0});
  ASSERT_TRUE(behind);
  EXPECT_EQ(behind->x, 0.0) << "the seam itself: x = 0, in [0, width)";
  // Every random direction (off the poles) has x in [0, width).
  for (const glm::dvec3& d : random_directions(5000, 11)) {
    const auto px = c.pixel(d);
    ASSERT_TRUE(px);
    EXPECT_GE(px->x, 0.0);
    EXPECT_LT(px->x, 256.0);
  }
}

TEST(EquirectangularProjection, DefaultOrientation) {
  const EquirectangularProjection e(256, 128);
  expect_direction(e.ray(128.0, 64.0), {0.0, 0.0, -1.0}, "centre = forward");
  expect_direction(e.ray(192.0, 64.0), {1.0, 0.0, 0.0}, "three quarters across = right (+x)");
  expect_direction(e.ray(64.0, 64.0), {-1.0, 0.0, 0.0}, "one quarter across = left");
  expect_direction(e.ray(0.0, 64.0), {0.0, 0.0, 1.0}, "left edge = backward");
  expect_direction(e.ray(256.0, 64.0), {0.0, 0.0, 1.0}, "right edge = backward");
  expect_direction(e.ray(128.0, 0.0), {0.0, 1.0, 0.0}, "top row = up");
  expect_direction(e.ray(17.0, 0.0), {0.0, 1.0, 0.0}, "every top position = up");
  expect_direction(e.ray(128.0, 128.0), {0.0, -1.0, 0.0}, "bottom row = down");
  expect_direction(e.ray(160.0, 32.0),
                   {std::sin(45.0 * kDeg) * std::cos(45.0 * kDeg), std::sin(45.0 * kDeg),
                    -std::cos(45.0 * kDeg) * std::cos(45.0 * kDeg)},
                   "longitude 45, latitude 45");
  expect_pixel(e.pixel({0.0, 0.0, -1.0}), 128.0, 64.0, "forward");
  expect_pixel(e.pixel({1.0, 0.0, 0.0}), 192.0, 64.0, "right");
  expect_pixel(e.pixel({0.0, 5.0, 0.0}), 128.0, 0.0, "up: the middle column");
  expect_pixel(e.pixel({0.0, -1.0, 0.0}), 128.0, 128.0, "down");
  expect_pixel(e.pixel({0.0, 0.0, 1.0}), 0.0, 64.0, "backward: the seam at x = 0");
  EXPECT_FALSE(e.pixel({0.0, 0.0, 0.0}));
  EXPECT_FALSE(e.ray(128.0, -1e-9)) << "past the pole";
  EXPECT_FALSE(e.ray(256.0 + 1e-9, 64.0)) << "past the seam";
  EXPECT_EQ(e.describe(), "equirectangular 360°×180° (longitude -180° to 180°, latitude -90° to 90°) 256×128");
}

TEST(EquirectangularProjection, PartialRangesPutTheirEdgesAtTheirAngles) {
  const EquirectangularProjection e(120, 50, {120.0, 240.0, -10.0, 60.0});
  auto at = [](double longitude_deg, double latitude_deg) {
    const double l = longitude_deg * kDeg, b = latitude_deg * kDeg;
    return glm::dvec3(std::cos(b) * std::sin(l), std::sin(b), -std::cos(b) * std::cos(l));
  };
  expect_direction(e.ray(0.0, 0.0), at(120.0, 60.0), "top-left");
  expect_direction(e.ray(120.0, 0.0), at(240.0, 60.0), "top-right");
  expect_direction(e.ray(0.0, 50.0), at(120.0, -10.0), "bottom-left");
  expect_direction(e.ray(60.0, 50.0 * 60.0 / 70.0), {0.0, 0.0, 1.0}, "centre column on the equator: backward");
  expect_pixel(e.pixel(at(-150.0, 0.0)), 90.0, 50.0 * 60.0 / 70.0, "-150° is 210°: across the ±180° seam");
  expect_pixel(e.pixel(at(10.0, 0.0)), 60.0 + 190.0 - 360.0, 50.0 * 60.0 / 70.0,
               "10°: within half a turn of the middle (180°) as -350°, off the image as it is");
  const EquirectangularProjection sky(200, 30, {-180.0, 180.0, 60.0, 90.0});
  expect_direction(sky.ray(100.0, 30.0), at(0.0, 60.0), "sky cap: bottom-centre at 60°");
  expect_direction(sky.ray(100.0, 0.0), {0.0, 1.0, 0.0}, "sky cap: top = zenith");
  EXPECT_TRUE(sky.ray(100.0, 150.0)) << "below the image, above the nadir: extends";
  EXPECT_FALSE(sky.ray(100.0, 30.0 * 180.0 / 30.0 + 1e-6)) << "below the nadir";
}

TEST(EquirectangularProjection, The360SeamHasNeighbouringRaysOnBothSides) {
  for (const EquirectangularParameters& range :
       {EquirectangularParameters{}, EquirectangularParameters{0.0, 360.0, -90.0, 90.0}}) {
    const EquirectangularProjection e(101, 37, range);
    const double bound = e.max_pixel_angle_rad();
    const double seam_longitude = range.longitude_min_deg * kDeg;
    for (int j = 0; j < 37; ++j) {
      const double y = j + 0.5;
      expect_direction(e.ray(0.0, y), *e.ray(101.0, y), "x = 0 and x = width are one column");
      const auto left = e.ray(0.5, y), right = e.ray(100.5, y);
      ASSERT_TRUE(left && right);
      EXPECT_LE(angle_between(*left, *right), bound) << j;
      EXPECT_NEAR(angle_between(*left, *right), angle_between(*e.ray(50.5, y), *e.ray(51.5, y)), 1e-12) << j;
    }
    // A hair either side of the seam's longitude lands at the two edges.
    auto at = [](double l) { return glm::dvec3(std::sin(l), 0.2, -std::cos(l)); };
    const auto after = e.pixel(at(seam_longitude + 1e-9)), before = e.pixel(at(seam_longitude - 1e-9));
    ASSERT_TRUE(after && before);
    EXPECT_NEAR(after->x, 0.0, 1e-6);
    EXPECT_NEAR(before->x, 101.0, 1e-6);
    EXPECT_LT(before->x, 101.0);
    for (const glm::dvec3& d : random_directions(5000, 13)) {
      const auto px = e.pixel(d);
      ASSERT_TRUE(px);
      EXPECT_GE(px->x, 0.0);
      EXPECT_LT(px->x, 101.0);
      EXPECT_GE(px->y, 0.0);
      EXPECT_LE(px->y, 37.0);
    }
  }
}

/// OpenGL's cube-map selection, written out from the specification's table
/// (not from the projection): the face of r and its (s, t).
struct GlTexel {
  CubeFace face;
  double s, t;
};
GlTexel gl_cube_texel(const glm::dvec3& r) {
  const double ax = std::abs(r.x), ay = std::abs(r.y), az = std::abs(r.z);
  double sc, tc, ma;
  CubeFace face;
  if (ax >= ay && ax >= az) {
    face = r.x > 0 ? CubeFace::positive_x : CubeFace::negative_x;
    sc = r.x > 0 ? -r.z : r.z;
    tc = -r.y;
    ma = ax;
  } else if (ay >= az) {
    face = r.y > 0 ? CubeFace::positive_y : CubeFace::negative_y;
    sc = r.x;
    tc = r.y > 0 ? r.z : -r.z;
    ma = ay;
  } else {
    face = r.z > 0 ? CubeFace::positive_z : CubeFace::negative_z;
    sc = r.z > 0 ? r.x : -r.x;
    tc = -r.y;
    ma = az;
  }
  return {face, 0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0)};
}

TEST(CubeFaceProjection, MatchesOpenGlCubeMapSelection) {
  std::vector<CubeFaceProjection> faces;
  for (int f = 0; f < 6; ++f) faces.emplace_back(64, static_cast<CubeFace>(f));
  for (const glm::dvec3& d : random_directions(20000, 3)) {
    const GlTexel gl = gl_cube_texel(d);
    const auto px = faces[static_cast<std::size_t>(gl.face)].pixel(d);
    ASSERT_TRUE(px);
    EXPECT_NEAR(px->x, gl.s * 64.0, 1e-11);
    EXPECT_NEAR(px->y, gl.t * 64.0, 1e-11) << "t = 0 is the top row (the first row glTexImage2D reads)";
  }
  // Face centres are the axes; the corners and edge midpoints of +x and +z.
  const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f)
    expect_direction(faces[f].ray(32.0, 32.0), axes[f], std::string(cube_face_name(faces[f].face())));
  expect_direction(faces[0].ray(0.0, 0.0), {1.0, 1.0, 1.0}, "+x top-left");
  expect_direction(faces[0].ray(64.0, 32.0), {1.0, 0.0, -1.0}, "+x right edge borders -z");
  expect_direction(faces[4].ray(64.0, 32.0), {1.0, 0.0, 1.0}, "+z right edge borders +x (mirror image of a camera)");
  expect_direction(faces[4].ray(32.0, 0.0), {0.0, 1.0, 1.0}, "+z top edge borders +y");
  expect_direction(faces[5].ray(64.0, 32.0), {-1.0, 0.0, -1.0}, "-z (forward) right edge borders -x");
  expect_direction(faces[2].ray(32.0, 0.0), {0.0, 1.0, -1.0}, "+y top edge borders -z");
  expect_direction(faces[3].ray(32.0, 0.0), {0.0, -1.0, 1.0}, "-y top edge borders +z");
  EXPECT_FALSE(faces[0].pixel({-1.0, 0.3, 0.2})) << "behind +x";
  EXPECT_FALSE(faces[0].pixel({0.0, 1.0, 0.0})) << "90° from +x";
  EXPECT_DOUBLE_EQ(glm::determinant(faces[0].frame()), -1.0) << "the cube map's frame is left-handed";
  EXPECT_EQ(faces[1].describe(), "cube face -x 64×64");
  EXPECT_EQ(cube_face_from_name("-y"), CubeFace::negative_y);
  EXPECT_FALSE(cube_face_from_name("y"));
}

TEST(CubeFaceProjection, SixFacesCoverTheSphereExactlyOnce) {
  for (int size : {1, 64, 65, 1000}) {
    std::vector<CubeFaceProjection> faces;
    for (int f = 0; f < 6; ++f) faces.emplace_back(size, static_cast<CubeFace>(f));
    int per_face[6] = {};
    for (const glm::dvec3& d : random_directions(60000, 5 + size)) {
      int hits = 0, hit_face = -1;
      for (int f = 0; f < 6; ++f) {
        const auto px = faces[f].pixel(d);
        if (px && px->x >= 0.0 && px->x < size && px->y >= 0.0 && px->y < size) {
          ++hits;
          hit_face = f;
        }
      }
      ASSERT_EQ(hits, 1) << size << ": (" << d.x << ", " << d.y << ", " << d.z << ")";
      EXPECT_EQ(static_cast<CubeFace>(hit_face), gl_cube_texel(d).face);
      ++per_face[hit_face];
    }
    for (int f = 0; f < 6; ++f) EXPECT_NEAR(per_face[f], 10000, 500) << size << " face " << f;
  }
}

TEST(MoreProjections, InvalidParametersThrowNamingThem) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto cylinder = [](int w, int h, CylindricalParameters p) { return [=] { CylindricalProjection(w, h, p); }; };
  expect_invalid(cylinder(0, 10, {}), {"width_px", "0", "[1, 65536]"});
  expect_invalid(cylinder(10, 10, {.horizontal_fov_deg = 0.0}), {"horizontal_fov_deg", "= 0", "(0, 360]", "degrees"});
  expect_invalid(cylinder(10, 10, {.horizontal_fov_deg = 360.5}), {"horizontal_fov_deg", "360.5"});
  expect_invalid(cylinder(10, 10, {.down_deg = -89.0}), {"down_deg", "-89", "(-89, 89)"});
  expect_invalid(cylinder(10, 10, {.up_deg = nan}), {"up_deg", "nan"});
  expect_invalid(cylinder(10, 10, {.down_deg = 30.0, .up_deg = 30.0}), {"down_deg", "up_deg", "less"});
  expect_invalid(cylinder(10, 10, {.yaw_deg = 390.0}), {"yaw_deg", "390", "[-360, 360]"});
  expect_invalid(cylinder(10, 10, {.pitch_deg = -360.5}), {"pitch_deg", "[-360, 360]"});
  expect_invalid(cylinder(10, 10, {.roll_deg = std::numeric_limits<double>::infinity()}), {"roll_deg", "inf"});
  EXPECT_NO_THROW(CylindricalProjection(1, 1, {.horizontal_fov_deg = 1e-6, .down_deg = -88.99, .up_deg = 88.99}));

  auto equirect = [](int w, int h, EquirectangularParameters p) { return [=] { EquirectangularProjection(w, h, p); }; };
  expect_invalid(equirect(10, 70000, {}), {"height_px", "70000"});
  expect_invalid(equirect(10, 10, {-400.0, 0.0, -90.0, 90.0}), {"longitude_min_deg", "-400", "[-360, 360]", "degrees"});
  expect_invalid(equirect(10, 10, {0.0, 361.0, -90.0, 90.0}), {"longitude_max_deg", "361"});
  expect_invalid(equirect(10, 10, {10.0, 10.0, -90.0, 90.0}), {"longitude_min_deg", "longitude_max_deg", "less"});
  expect_invalid(equirect(10, 10, {-180.0, 200.0, -90.0, 90.0}), {"longitude_max_deg", "380", "(0, 360]"});
  expect_invalid(equirect(10, 10, {-180.0, 180.0, -91.0, 90.0}), {"latitude_min_deg", "-91", "[-90, 90]"});
  expect_invalid(equirect(10, 10, {-180.0, 180.0, -90.0, nan}), {"latitude_max_deg", "nan"});
  expect_invalid(equirect(10, 10, {-180.0, 180.0, 20.0, 10.0}), {"latitude_min_deg", "latitude_max_deg", "less"});
  EXPECT_NO_THROW(EquirectangularProjection(1, 1, {-360.0, 0.0, 89.0, 90.0}));

  expect_invalid([] { CubeFaceProjection(0, CubeFace::positive_x); }, {"width_px", "0"});
  expect_invalid([] { CubeFaceProjection(8, static_cast<CubeFace>(6)); }, {"face", "6", "+x, -x, +y, -y, +z, -z"});
}

TEST(MoreProjections, MaxPixelAngleBoundsNeighbouringRays) { expect_tight_pixel_angle_bounds(all_cases()); }

TEST(MoreProjections, GpuLayoutReproducesTheRaysInFloat) {
  for (const Named& c : all_cases()) {
    const Projection& p = *c.projection;
    const GpuProjection g = p.gpu();
    const ProjectionKind expected = dynamic_cast<const CylindricalProjection*>(&p) ? ProjectionKind::cylindrical
                                    : dynamic_cast<const EquirectangularProjection*>(&p)
                                        ? ProjectionKind::equirectangular
                                        : ProjectionKind::cube_face;
    EXPECT_EQ(g.kind, expected) << c.name;
    double worst = 0.0;
    for (int j = 0; j < p.height(); ++j)
      for (int i = 0; i < p.width(); ++i) {
        const double x = i + 0.5, y = j + 0.5;
        const auto cpu = p.ray(x, y);
        const auto gpu = emulate_glsl(g, glm::vec2(static_cast<float>(x), static_cast<float>(y)));
        ASSERT_TRUE(cpu && gpu) << c.name << " pixel " << i << ", " << j;
        worst = std::max(worst, angle_between(*cpu, glm::dvec3(*gpu)));
      }
    EXPECT_LT(worst, 2e-6) << c.name;
    std::printf("%-28s float emulation of projection.glsl: max %.3g rad\n", c.name.c_str(), worst);
  }
  EXPECT_EQ(static_cast<int>(ProjectionKind::cylindrical), 2);
  EXPECT_EQ(static_cast<int>(ProjectionKind::equirectangular), 3);
  EXPECT_EQ(static_cast<int>(ProjectionKind::cube_face), 4);
}

// ---- the JSON factory

std::unique_ptr<Projection> make(const std::string& text, int w = 64, int h = 48) {
  return make_projection(nlohmann::json::parse(text), w, h, "dome.json", "/viewports/0/projection");
}

TEST(ProjectionFactory, BuildsEveryType) {
  EXPECT_EQ(make(R"({"type": "fisheye", "fov_deg": 180, "tilt_deg": 0})", 64, 64)->describe(), "fisheye 180° 64×64");
  EXPECT_EQ(make(R"({"type": "fisheye", "fov_deg": 210, "tilt_deg": 30, "rotation_deg": 90, "centre_x_px": 30,
                    "centre_y_px": 20, "radius_px": 40})")
                ->describe(),
            FisheyeProjection(64, 48,
                              {.fov_deg = 210.0,
                               .tilt_deg = 30.0,
                               .centre_x_px = 30.0,
                               .centre_y_px = 20.0,
                               .radius_px = 40.0,
                               .rotation_deg = 90.0})
                .describe());
  EXPECT_EQ(make(R"({"type": "fisheye"})")->describe(), "fisheye 180° 64×48");
  EXPECT_EQ(make(R"({"type": "planar", "fov_deg": 60})")->describe(),
            PlanarProjection::symmetric(64, 48, 60.0).describe());
  EXPECT_EQ(make(R"({"type": "planar", "fov_deg": 60, "yaw_deg": 90})")->gpu().params,
            PlanarProjection(64, 48,
                             [] {
                               PlanarFrustum f = PlanarProjection::symmetric(64, 48, 60.0).frustum();
                               f.yaw_deg = 90.0;
                               return f;
                             }())
                .gpu()
                .params);
  EXPECT_EQ(make(R"({"type": "planar", "left_deg": -40, "right_deg": 40, "down_deg": -25, "up_deg": 25,
                    "yaw_deg": 10, "pitch_deg": -5, "roll_deg": 2})")
                ->describe(),
            "planar 80°×50° (left -40° right 40° down -25° up 25°) 64×48, yaw 10° pitch -5° roll 2°");
  EXPECT_EQ(make(R"({"type": "cylindrical", "horizontal_fov_deg": 270, "down_deg": -20, "up_deg": 50,
                    "yaw_deg": 45})")
                ->describe(),
            "cylindrical 270°×70° (down -20° up 50°) 64×48, yaw 45° pitch 0° roll 0°");
  EXPECT_EQ(make(R"({"type": "cylindrical"})")->describe(), "cylindrical 360°×90° (down -45° up 45°) 64×48");
  EXPECT_EQ(make(R"({"type": "equirectangular"})")->describe(),
            "equirectangular 360°×180° (longitude -180° to 180°, latitude -90° to 90°) 64×48");
  EXPECT_EQ(make(R"({"type": "equirectangular", "longitude_min_deg": -90, "longitude_max_deg": 90,
                    "latitude_min_deg": 0, "latitude_max_deg": 90})")
                ->describe(),
            "equirectangular 180°×90° (longitude -90° to 90°, latitude 0° to 90°) 64×48");
  for (const char* face : {"+x", "-x", "+y", "-y", "+z", "-z"}) {
    const auto p = make(std::string(R"({"type": "cube", "face": ")") + face + "\"}", 32, 32);
    const auto* cube = dynamic_cast<const CubeFaceProjection*>(p.get());
    ASSERT_TRUE(cube) << face;
    EXPECT_EQ(cube_face_name(cube->face()), face);
  }
}

// Calibration tools write angles in [0, 360): every orientation angle of a
// viewport's projection is read in [−360, 360] and gives the rotation of the
// same angle in (−180, 180] (yaw_deg 326.7 was once refused).
TEST(ProjectionFactory, OrientationAnglesIn0To360GiveTheSameRays) {
  const auto rays_equal = [](const Projection& a, const Projection& b) {
    for (double y = 0.5; y < a.height(); y += 7.0)
      for (double x = 0.5; x < a.width(); x += 7.0) {
        const auto ra = a.ray(x, y), rb = b.ray(x, y);
        ASSERT_EQ(ra.has_value(), rb.has_value()) << x << ", " << y;
        if (ra) {
          EXPECT_LT(angle_between(*ra, *rb), 1e-12) << a.describe() << " vs " << b.describe();
        }
      }
  };
  const auto planar_wrapped = make(R"({"type": "planar", "fov_deg": 60, "yaw_deg": 326.7, "pitch_deg": 340,
                                       "roll_deg": 270})");
  const auto planar_signed = make(R"({"type": "planar", "fov_deg": 60, "yaw_deg": -33.3, "pitch_deg": -20,
                                      "roll_deg": -90})");
  rays_equal(*planar_wrapped, *planar_signed);
  EXPECT_EQ(planar_wrapped->describe(), planar_signed->describe());  // kept normalized
  // Over the top: pitch 120 = pitch 60 with yaw and roll turned half way round.
  rays_equal(*make(R"({"type": "planar", "fov_deg": 60, "yaw_deg": 10, "pitch_deg": 120, "roll_deg": 0})"),
             *make(R"({"type": "planar", "fov_deg": 60, "yaw_deg": -170, "pitch_deg": 60, "roll_deg": 180})"));
  rays_equal(*make(R"({"type": "cylindrical", "horizontal_fov_deg": 120, "yaw_deg": 350, "roll_deg": 355})"),
             *make(R"({"type": "cylindrical", "horizontal_fov_deg": 120, "yaw_deg": -10, "roll_deg": -5})"));
  rays_equal(*make(R"({"type": "fisheye", "fov_deg": 200, "tilt_deg": 330, "rotation_deg": 270})", 64, 64),
             *make(R"({"type": "fisheye", "fov_deg": 200, "tilt_deg": -30, "rotation_deg": -90})", 64, 64));
}

void expect_config_error(const std::string& text, const std::vector<std::string>& parts, int w = 64, int h = 48) {
  try {
    make(text, w, h);
    ADD_FAILURE() << text << ": no error";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_TRUE(what.starts_with("dome.json: /viewports/0/projection")) << what;
    for (const std::string& part : parts) EXPECT_NE(what.find(part), std::string::npos) << what << " lacks " << part;
    std::printf("  %s\n", what.c_str());
  }
}

TEST(ProjectionFactory, RejectsInvalidSpecsNamingSourcePointerValueAndRange) {
  expect_config_error(R"({"type": "fisheye", "fov_deg": 400})",
                      {"dome.json: /viewports/0/projection/fov_deg = 400: must be in [1, 360] degrees"});
  expect_config_error(R"({"type": "planar", "fov_deg": 200})",
                      {"/viewports/0/projection/fov_deg = 200: must be in (0, 178) degrees"});
  expect_config_error(R"({"type": "planar", "left_deg": -90, "right_deg": 40, "down_deg": -25, "up_deg": 25})",
                      {"/projection/left_deg = -90: must be in (-89, 89) degrees"});
  expect_config_error(R"({"type": "planar", "left_deg": 30, "right_deg": 10, "down_deg": -25, "up_deg": 25})",
                      {"/projection/left_deg = 30", "must be less than right_deg = 10"});
  expect_config_error(R"({"type": "planar", "left_deg": -30, "right_deg": 10, "down_deg": -25})",
                      {"/projection/up_deg: missing required key"});
  expect_config_error(R"({"type": "planar", "fov_deg": 60, "left_deg": -30})", {"either fov_deg or"});
  expect_config_error(R"({"type": "planar"})", {"/viewports/0/projection: give either fov_deg"});
  expect_config_error(R"({"type": "fisheye", "tilt_deg": 120})",
                      {"/projection/tilt_deg = 120: must be in [-90, 90] degrees (or the same tilt plus or minus 360"});
  expect_config_error(R"({"type": "cylindrical", "roll_deg": -361})", {"/projection/roll_deg = -361", "[-360, 360]"});
  expect_config_error(
      R"({"type": "planar", "fov_deg": 60, "yaw_deg": 400})",
      {"/projection/yaw_deg = 400: must be in [-360, 360] degrees ([0, 360) and (-180, 180] both read)"});
  expect_config_error(R"({"type": "fisheye", "fov": 180})",
                      {"/projection/fov: unknown key", "allowed for type \"fisheye\": type, fov_deg, tilt_deg"});
  expect_config_error(R"({"type": "fisheye", "tilt_deg": "up"})",
                      {"/projection/tilt_deg = \"up\": must be a number (degrees)"});
  expect_config_error(R"({"type": "fisheye", "radius_px": 0})",
                      {"/projection/radius_px = 0: must be in (0, 1e+06] px"});
  expect_config_error(R"({"type": "cylindrical", "horizontal_fov_deg": 361})",
                      {"/projection/horizontal_fov_deg = 361: must be in (0, 360] degrees"});
  expect_config_error(R"({"type": "cylindrical", "down_deg": 10, "up_deg": -10})",
                      {"/projection/down_deg = 10 must be less than up_deg = -10"});
  expect_config_error(R"({"type": "equirectangular", "latitude_max_deg": 95})",
                      {"/projection/latitude_max_deg = 95: must be in [-90, 90] degrees"});
  expect_config_error(R"({"type": "equirectangular", "longitude_min_deg": -200, "longitude_max_deg": 200})",
                      {"longitude_max_deg − longitude_min_deg = 400: must be in (0, 360] degrees"});
  expect_config_error(R"({"type": "cube", "face": "x"})",
                      {"/projection/face = \"x\": must be one of \"+x\", \"-x\", \"+y\", \"-y\", \"+z\", \"-z\""}, 32,
                      32);
  expect_config_error(R"({"type": "cube", "face": "+x"})", {"/viewports/0/projection: a cube face is square", "64×48"});
  expect_config_error(R"({"type": "cube"})", {"/projection/face: missing required key"}, 32, 32);
  expect_config_error(R"({"type": "mercator"})",
                      {"/projection/type = \"mercator\": must be one of \"planar\", \"fisheye\", \"cylindrical\", "
                       "\"equirectangular\", \"cube\""});
  expect_config_error(R"({"fov_deg": 180})", {"/projection/type: missing required key"});
  expect_config_error(R"([1, 2])", {"must be a JSON object"});
  expect_config_error(R"({"type": "fisheye"})", {"image width_px = 0: must be in [1, 65536] px"}, 0, 48);
  // Without a pointer the keys are top-level pointers.
  try {
    make_projection(nlohmann::json::parse(R"({"type": "fisheye", "fov_deg": 0})"), 8, 8, "cli");
    ADD_FAILURE();
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "cli: /fov_deg = 0: must be in [1, 360] degrees");
  }
}

}  // namespace
}  // namespace zenith::warp
