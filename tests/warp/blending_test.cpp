// Edge blending (warp/blending.h): the automatic weights of the six-projector
// dome sum to one wherever projectors overlap and cover the whole dome, the
// masks are smooth, file masks decode with their gamma, and the output stage
// follows MPCDI's P·α·(1 − β) + β.
#include "warp/blending.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <vector>

#include "core/units.h"
#include "warp/fisheye_projection.h"
#include "warp_file_test_support.h"

namespace zenith::warp {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::expect_error;
using testing::make_grey_png;
using testing::ScratchDir;

const fs::path kViewports = fs::path(ZENITH_SOURCE_DIR) / "configs" / "viewports";
using core::kDeg;

/// The six-projector dome at another output size (the frusta are size-independent).
ViewportConfig dome6(int width_px, int height_px) {
  const fs::path path = kViewports / "dome-6-projectors.json";
  json j = json::parse(std::ifstream(path));
  for (json& o : j["outputs"]) o["size"] = {width_px, height_px};
  return parse_viewport_config(j, path.string(), kViewports);
}

/// Camera-frame direction at elevation e above the horizon and azimuth a
/// (clockwise from forward −z toward +x), degrees.
glm::dvec3 dome_direction(double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * kDeg, a = azimuth_deg * kDeg;
  return {std::cos(e) * std::sin(a), std::sin(e), -std::cos(e) * std::cos(a)};
}

/// Bilinear sample of a mask at a continuous pixel position (clamped at the edges).
double sample(const BlendMask& m, double x_px, double y_px) {
  const double fx = std::clamp(x_px - 0.5, 0.0, m.width - 1.0), fy = std::clamp(y_px - 0.5, 0.0, m.height - 1.0);
  const int x0 = std::min(int(fx), m.width - 2), y0 = std::min(int(fy), m.height - 2);
  const double tx = fx - x0, ty = fy - y0;
  return (1 - ty) * ((1 - tx) * m.at(x0, y0) + tx * m.at(x0 + 1, y0)) +
         ty * ((1 - tx) * m.at(x0, y0 + 1) + tx * m.at(x0 + 1, y0 + 1));
}

TEST(Blending, SixProjectorDomeIsCoveredAndWeightsSumToOne) {
  const ViewportConfig c = dome6(1920, 1200);
  const AutoBlend blend(c);
  std::vector<double> w(c.outputs.size());
  int directions = 0, overlapped = 0, max_cover = 0;
  double worst = 0.0;
  for (double e = 0.0; e <= 90.0; e += 1.0)
    for (double a = 0.0; a < 360.0; a += 1.0) {
      const glm::dvec3 d = dome_direction(e, a);
      const double raw_sum = blend.weights(d, w);
      int cover = 0;
      for (std::size_t j = 0; j < c.outputs.size(); ++j)
        if (c.outputs[j].projection->pixel(d).has_value()) {
          const auto p = *c.outputs[j].projection->pixel(d);
          cover += p.x >= 0 && p.x <= 1920 && p.y >= 0 && p.y <= 1200;
        }
      ++directions;
      ASSERT_GE(cover, 1) << "uncovered at elevation " << e << "°, azimuth " << a << "°";
      ASSERT_GT(raw_sum, 0.0) << "elevation " << e << "°, azimuth " << a << "°";
      double sum = 0.0;
      for (double x : w) sum += x;
      worst = std::max(worst, std::abs(sum - 1.0));
      overlapped += cover >= 2;
      max_cover = std::max(max_cover, cover);
    }
  EXPECT_LE(worst, 1e-12);
  EXPECT_GT(overlapped, directions / 10) << "the projectors should overlap";
  std::printf("[dome-6] %d dome directions (1° grid), %d seen by ≥ 2 projectors, at most %d; |Σw − 1| ≤ %.1e\n",
              directions, overlapped, max_cover, worst);
}

// The masks as images: each projector's stored mask, sampled where the
// projector sees a dome direction, sums to 1 ± 0.5 % over the projectors.
TEST(Blending, SixProjectorMasksSumToOneWhereProjectorsOverlap) {
  const ViewportConfig c = dome6(960, 600);  // half size: a quarter of the work, same geometry
  const AutoBlend blend(c);
  std::vector<BlendMask> masks;
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < c.outputs.size(); ++i) masks.push_back(blend.mask(i));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double worst_overlap = 0.0, worst_single = 0.0;
  int overlapped = 0;
  for (double e = 0.0; e <= 90.0; e += 0.5)
    for (double a = 0.0; a < 360.0; a += 0.5) {
      const glm::dvec3 d = dome_direction(e, a);
      double sum = 0.0;
      int cover = 0;
      for (std::size_t j = 0; j < c.outputs.size(); ++j) {
        const auto p = c.outputs[j].projection->pixel(d);
        if (!p || p->x < 0 || p->x > 960 || p->y < 0 || p->y > 600) continue;
        ++cover;
        sum += sample(masks[j], p->x, p->y);
      }
      ASSERT_GE(cover, 1);
      if (cover >= 2) {
        ++overlapped;
        worst_overlap = std::max(worst_overlap, std::abs(sum - 1.0));
      } else {
        worst_single = std::max(worst_single, std::abs(sum - 1.0));
      }
    }
  EXPECT_LE(worst_overlap, 0.005);
  EXPECT_LE(worst_single, 0.005);
  std::printf(
      "[dome-6 masks 960x600, %.2f s] %d overlapped directions (0.5° grid): max |Σα − 1| = %.2e; "
      "single cover: %.2e\n",
      seconds, overlapped, worst_overlap, worst_single);
}

TEST(Blending, MasksAreSmooth) {
  const ViewportConfig c = dome6(480, 300);
  const AutoBlend blend(c);
  const double ramp_px = 0.1 * 300;
  for (std::size_t i = 0; i < c.outputs.size(); ++i) {
    const BlendMask m = blend.mask(i);
    double jump = 0.0, lo = 1.0, hi = 0.0;
    auto above_horizon = [&](int x, int y) { return c.outputs[i].projection->ray(x + 0.5, y + 0.5)->y >= 0.0; };
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) {
        lo = std::min(lo, double(m.at(x, y)));
        hi = std::max(hi, double(m.at(x, y)));
        // On the dome only: below the horizon (no screen) the band projectors'
        // bottom edges end together and the weights split 0 / 0 abruptly.
        if (!above_horizon(x, y)) continue;
        if (x + 1 < m.width && above_horizon(x + 1, y))
          jump = std::max(jump, double(std::abs(m.at(x + 1, y) - m.at(x, y))));
        if (y + 1 < m.height && above_horizon(x, y + 1))
          jump = std::max(jump, double(std::abs(m.at(x, y + 1) - m.at(x, y))));
      }
    // A single smoothstep ramp rises by at most 1.5 / ramp per pixel; normalized
    // crossing ramps are steeper where an overlap is narrower than a ramp or
    // three ramps meet (measured: 1.4 to 2.02 / ramp on this dome).
    EXPECT_LE(jump, 2.5 / ramp_px) << c.outputs[i].name;
    EXPECT_GE(lo, 0.0);
    EXPECT_LE(hi, 1.0);
    EXPECT_NEAR(hi, 1.0, 1e-6) << "every projector has a part it lights alone";
    std::printf("[smooth] %s: max jump on the dome %.4f per px (1 / ramp = %.4f)\n", c.outputs[i].name.c_str(), jump,
                1.0 / ramp_px);
  }
}

TEST(Blending, OnlyAutoOutputsShareTheirLight) {
  json j = json::parse(R"({"zenith_viewports": 1, "name": "pair", "outputs": [
    {"name": "left", "size": [100, 50], "projection": {"type": "planar", "left_deg": -40, "right_deg": 10,
     "down_deg": -20, "up_deg": 20}, "blend": "auto"},
    {"name": "right", "size": [100, 50], "projection": {"type": "planar", "left_deg": -10, "right_deg": 40,
     "down_deg": -20, "up_deg": 20}, "blend": {"type": "auto", "width_fraction": 0.2}},
    {"name": "plain", "size": [100, 50], "projection": {"type": "planar", "fov_deg": 80}}]})");
  const ViewportConfig c = parse_viewport_config(j, "pair.json", ".");
  const AutoBlend blend(c);
  EXPECT_TRUE(blend.participates(0));
  EXPECT_FALSE(blend.participates(2));
  // Straight ahead both pairs overlap: the weights split the light.
  std::vector<double> w(3);
  blend.weights({0, 0, -1}, w);
  EXPECT_NEAR(w[0] + w[1], 1.0, 1e-12);
  EXPECT_EQ(w[2], 0.0);
  EXPECT_GT(w[0], 0.1);
  EXPECT_GT(w[1], 0.1);
  // The ramp: D / r with r = 0.1 · 50 = 5 px for "left", 10 px for "right".
  EXPECT_DOUBLE_EQ(blend.raw_weight_at(0, 2.5, 25.0), 0.5 * 0.5 * (3.0 - 2.0 * 0.5));
  EXPECT_DOUBLE_EQ(blend.raw_weight_at(1, 5.0, 25.0), 0.5);
  EXPECT_EQ(blend.raw_weight_at(0, 50.0, 25.0), 1.0);
  EXPECT_EQ(blend.raw_weight_at(0, -1.0, 25.0), 0.0);
  expect_error([&] { (void)blend.mask(2); }, {"no automatic blend"});
  const BlendMask plain = output_blend_mask(c, 2);
  EXPECT_EQ(*std::min_element(plain.alpha.begin(), plain.alpha.end()), 1.0f);
}

TEST(Blending, FisheyeCoverageEndsAtTheImageCircle) {
  // Two tilted fisheyes: the raw weight falls to zero at each image circle
  // (the distance transform of the pixels without a ray), not at the square's edge.
  json j = json::parse(R"({"zenith_viewports": 1, "name": "two", "outputs": [
    {"name": "a", "size": [80, 80], "projection": {"type": "fisheye", "fov_deg": 180, "tilt_deg": 30}, "blend": "auto"},
    {"name": "b", "size": [80, 80], "projection": {"type": "fisheye", "fov_deg": 180, "tilt_deg": -30},
     "blend": "auto"}]})");
  const ViewportConfig c = parse_viewport_config(j, "two.json", ".");
  const AutoBlend blend(c);
  // The circle has radius 40 px about (40, 40): at (40, 1) the border is about 1 px away.
  EXPECT_NEAR(blend.border_distance_px(0, 40.0, 1.0), 1.0, 0.6);
  EXPECT_NEAR(blend.border_distance_px(0, 40.0, 40.0), 40.0, 1.5);  // the transform is on pixel centres
  // A corner of the square is outside the circle.
  EXPECT_LE(blend.border_distance_px(0, 3.0, 3.0), 0.5);
  const BlendMask m = blend.mask(0);
  EXPECT_EQ(m.at(0, 0), 0.0f);
  EXPECT_NEAR(m.at(40, 40), 0.5, 0.2);  // the shared zenith, seen by both
  std::vector<double> w(2);
  for (double e = 0.0; e <= 90.0; e += 3.0)
    for (double a = 0.0; a < 360.0; a += 3.0) {
      const double raw = blend.weights(dome_direction(e, a), w);
      if (raw > 0.0) {
        EXPECT_NEAR(w[0] + w[1], 1.0, 1e-12);
      }
    }
}

TEST(Blending, FileMasksDecodeWithTheirGamma) {
  ScratchDir dir("blend_mask");
  std::vector<std::uint16_t> grey = {0, 16384, 32768, 65535, 65535, 0};
  const fs::path path = dir.write("mask.png", make_grey_png(3, 2, grey));
  const BlendMask linear = load_blend_mask(path, 1.0, 3, 2);
  const BlendMask gamma = load_blend_mask(path, 2.2, 3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      const double stored = grey[static_cast<std::size_t>(y * 3 + x)] / 65535.0;
      EXPECT_NEAR(linear.at(x, y), stored, 1e-6);
      EXPECT_NEAR(gamma.at(x, y), std::pow(stored, 2.2), 1e-6);
    }
  expect_error([&] { (void)load_blend_mask(path, 1.0, 4, 2); }, {"mask.png", "3x2 px", "4x2"});
  const fs::path junk = dir.write("junk.png", "not a png");
  expect_error([&] { (void)load_blend_mask(junk, 1.0, 3, 2); }, {"junk.png"});

  // Through a config: output_blend_mask reads the file.
  json j = json::parse(R"({"zenith_viewports": 1, "name": "f", "outputs": [
    {"name": "a", "size": [3, 2], "projection": {"type": "planar", "fov_deg": 60},
     "blend": {"file": "mask.png", "gamma": 2.2}}]})");
  const ViewportConfig c = parse_viewport_config(j, "f.json", dir.path());
  EXPECT_NEAR(output_blend_mask(c, 0).at(1, 0), std::pow(16384 / 65535.0, 2.2), 1e-6);
}

TEST(Blending, BlackLevelClosedForm) {
  // P' = P·α·(1 − β) + β: black stays at β, full white with α = 1 stays at 1,
  // and two projectors blended with α and 1 − α show (1 − β)·P + 2β.
  for (double beta : {0.0, 0.02, 0.1, 0.5})
    for (double alpha : {0.0, 0.25, 0.5, 1.0})
      for (double p : {0.0, 0.3, 1.0}) {
        EXPECT_DOUBLE_EQ(blend_display_value(p, alpha, beta), p * alpha * (1.0 - beta) + beta);
        EXPECT_NEAR(blend_display_value(p, alpha, beta) + blend_display_value(p, 1.0 - alpha, beta),
                    p * (1.0 - beta) + 2.0 * beta, 1e-15);
      }
  EXPECT_EQ(blend_display_value(0.0, 0.7, 0.05), 0.05);
  EXPECT_EQ(blend_display_value(1.0, 1.0, 0.05), 1.0);

  BlendMask m{2, 3, {1.0f, 0.5f, 0.25f, 0.0f, 1.0f, 1.0f}};
  std::vector<float> rows = {1, 1, 1, 0.5f, 0.5f, 0.5f, 0.2f, 0.4f, 0.8f, 1, 1, 1};  // rows 1 and 2... of 2 px
  apply_blend(rows, 1, 2, m, 0.1);
  EXPECT_FLOAT_EQ(rows[0], 1.0f * 0.25f * 0.9f + 0.1f);
  EXPECT_FLOAT_EQ(rows[3], 0.1f);  // α = 0: the black level only
  EXPECT_FLOAT_EQ(rows[8], 0.8f * 0.9f + 0.1f);
  EXPECT_FLOAT_EQ(rows[11], 0.9f + 0.1f);
  std::vector<float> wrong(5);
  expect_error([&] { apply_blend(wrong, 0, 1, m, 0.0); }, {"do not fit"});
  std::vector<float> past(6 * 2);
  expect_error([&] { apply_blend(past, 2, 2, m, 0.0); }, {"do not fit"});
}

}  // namespace
}  // namespace zenith::warp
