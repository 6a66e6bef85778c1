#pragma once
// Helpers of the projection tests (projection_test.cpp, more_projections_test.cpp):
// checks of rays and pixels, sample positions along an image's side, named test
// cases, checks of parameter errors, the measured pixel angle and its bound, and
// shaders/projection.glsl transcribed to C++ float.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "warp/projection.h"

namespace zenith::warp::testing {

/// Angle between two directions (need not be unit), accurate at small and large angles.
inline double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

/// Expects a unit ray within 1e-12 rad of `expected`.
inline void expect_direction(const std::optional<glm::dvec3>& actual, const glm::dvec3& expected,
                             const std::string& what) {
  ASSERT_TRUE(actual.has_value()) << what;
  EXPECT_NEAR(glm::length(*actual), 1.0, 1e-14) << what;
  EXPECT_LT(angle_between(*actual, expected), 1e-12)
      << what << ": (" << actual->x << ", " << actual->y << ", " << actual->z << ") expected (" << expected.x << ", "
      << expected.y << ", " << expected.z << ")";
}

/// Expects a pixel position within 1e-9 px of (x, y).
inline void expect_pixel(const std::optional<glm::dvec2>& actual, double x, double y, const std::string& what) {
  ASSERT_TRUE(actual.has_value()) << what;
  EXPECT_NEAR(actual->x, x, 1e-9) << what;
  EXPECT_NEAR(actual->y, y, 1e-9) << what;
}

/// Sample positions along one axis of an image `size` pixels long: a regular
/// grid plus points within a hair of both edges and of the centre.
inline std::vector<double> sample_positions(int size) {
  const double n = size;
  std::vector<double> out = {0.0,   1e-9,         1e-6,    1e-3,     0.5,      n / 2 - 1e-7,
                             n / 2, n / 2 + 1e-7, n - 0.5, n - 1e-3, n - 1e-6, n};
  for (int i = 0; i <= 40; ++i) out.push_back(n * i / 40.0);
  return out;
}

/// A projection under test and the name its failures are reported with.
struct Named {
  std::string name;
  std::shared_ptr<const Projection> projection;
};

/// Expects `make` to throw std::invalid_argument whose message contains every
/// string of `parts` (the parameter's name, its value, the range).
inline void expect_invalid(const std::function<void()>& make, const std::vector<std::string>& parts) {
  try {
    make();
    ADD_FAILURE() << "no exception; expected one naming " << parts.front();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const std::string& part : parts) EXPECT_NE(what.find(part), std::string::npos) << what << " lacks " << part;
  }
}

/// The largest angle between the rays of two points of one pixel, over
/// neighbouring pixel centres (horizontal, vertical, both diagonals) and each
/// pixel's opposite corners, where both have rays.
inline double max_neighbour_angle(const Projection& p) {
  double worst = 0.0;
  auto pair = [&](double x0, double y0, double x1, double y1) {
    const auto a = p.ray(x0, y0), b = p.ray(x1, y1);
    if (a && b) worst = std::max(worst, angle_between(*a, *b));
  };
  for (int j = 0; j < p.height(); ++j)
    for (int i = 0; i < p.width(); ++i) {
      const double x = i + 0.5, y = j + 0.5;
      pair(x, y, x + 1.0, y);
      pair(x, y, x, y + 1.0);
      pair(x, y, x + 1.0, y + 1.0);
      pair(x + 1.0, y, x, y + 1.0);
      pair(i, j, i + 1.0, j + 1.0);
      pair(i + 1.0, j, i, j + 1.0);
    }
  return worst;
}

/// Expects each case's max_pixel_angle_rad() to bound max_neighbour_angle()
/// and to be tight (the measured angle above half of it); prints both.
inline void expect_tight_pixel_angle_bounds(const std::vector<Named>& cases) {
  for (const Named& c : cases) {
    const double bound = c.projection->max_pixel_angle_rad();
    const double measured = max_neighbour_angle(*c.projection);
    EXPECT_LE(measured, bound * (1.0 + 1e-12)) << c.name;
    EXPECT_GT(measured, 0.5 * bound) << c.name << ": the bound is loose";
    std::printf("%-30s max neighbour angle %.6g rad, bound %.6g rad (ratio %.4f)\n", c.name.c_str(), measured, bound,
                measured / bound);
  }
}

/// shaders/projection.glsl, transcribed to C++ float: the same operations on the
/// 16 floats of gpu(), for every kind with a closed form. The GPU test
/// (tests/render/projection_gpu_test.cpp) runs the shader itself.
inline std::optional<glm::vec3> emulate_glsl(const GpuProjection& g, glm::vec2 pixel) {
  auto xyz = [&](int i) { return glm::vec3(g.params[i][0], g.params[i][1], g.params[i][2]); };
  switch (g.kind) {
    case ProjectionKind::ray_table: ADD_FAILURE() << "ray tables have no closed form to emulate"; return std::nullopt;
    case ProjectionKind::planar:
    case ProjectionKind::cube_face:
      return glm::normalize((pixel.x - g.params[0][3]) * xyz(0) + (pixel.y - g.params[1][3]) * xyz(1) + xyz(2));
    case ProjectionKind::fisheye: {
      const auto& circle = g.params[0];
      const glm::vec2 offset(pixel.x - circle[0], circle[1] - pixel.y);
      const float r = glm::length(offset);
      const float theta = r * circle[2];
      if (theta > circle[3]) return std::nullopt;
      const float s = r > 0.0f ? std::sin(theta) / r : circle[2];
      return glm::normalize(s * (offset.x * xyz(1) + offset.y * xyz(2)) + std::cos(theta) * xyz(3));
    }
    case ProjectionKind::cylindrical: {
      const auto& grid = g.params[0];
      const float from_centre_x = pixel.x - grid[0];
      if (std::abs(from_centre_x) > g.params[2][3]) return std::nullopt;
      const float phi = from_centre_x * grid[1];
      const float v = g.params[1][3] + (pixel.y - grid[2]) * grid[3];
      return glm::normalize(std::sin(phi) * xyz(1) + v * xyz(2) - std::cos(phi) * xyz(3));
    }
    case ProjectionKind::equirectangular: {
      const auto& grid = g.params[0];
      const auto& centre = g.params[1];
      const float from_centre_x = pixel.x - grid[0];
      const float latitude = centre[1] + (pixel.y - grid[2]) * grid[3];
      if (std::abs(from_centre_x) > centre[2] || std::abs(latitude) > centre[3]) return std::nullopt;
      const float longitude = centre[0] + from_centre_x * grid[1];
      const float cos_latitude = std::cos(latitude);
      return glm::normalize(
          glm::vec3(cos_latitude * std::sin(longitude), std::sin(latitude), -cos_latitude * std::cos(longitude)));
    }
  }
  return std::nullopt;
}

}  // namespace zenith::warp::testing
