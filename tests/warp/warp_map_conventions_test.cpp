// Warp map conventions (warp/warp_map_conventions.h) and their checks
// (warp/warp_map_checks.h): PFM warp maps written here the way other tools
// write them (E&S offsets, SGCT's top-first rows with v up) load to the same
// mesh as zenith's own convention once configured, read with the defaults they
// give the mirrored mapping, and suspicious maps are warned about.
#include "warp/warp_map_conventions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "tests/warp/warp_file_test_support.h"
#include "warp/fisheye_projection.h"
#include "warp/viewport_config.h"
#include "warp/warp_map_checks.h"
#include "warp/warp_mesh.h"
#include "warp/warped_projection.h"

namespace zenith::warp {
namespace {

using nlohmann::json;
using testing::expect_error;
using testing::LogCapture;
using testing::make_pfm;
using testing::ScratchDir;

constexpr int kColumns = 9, kRows = 7;

double node_s(int x) { return static_cast<double>(x) / (kColumns - 1); }
double node_t(int y) { return static_cast<double>(y) / (kRows - 1); }
// A small smooth distortion: the offset of the source point from the node's place.
double offset_u(int x, int y) { return 0.04 * std::sin(3.14159265358979 * node_s(x)) * (node_t(y) - 0.5); }
double offset_v(int x, int y) { return 0.01 - 0.03 * node_s(x) * node_t(y); }
// The absolute source point in zenith's convention (v down).
double true_u(int x, int y) { return node_s(x) + offset_u(x, y); }
double true_v(int x, int y) { return node_t(y) + offset_v(x, y); }

/// A warp map of columns × rows nodes holding (u(x, y), v(x, y), 0), little
/// endian; `top_first`: the top row stored first (else the classic bottom first).
std::string uv_pfm(int columns, int rows, double (*u)(int, int), double (*v)(int, int), bool top_first) {
  return make_pfm(
      columns, rows, 3,
      [&](int x, int y, int c) {
        return static_cast<float>(c == 0 ? u(x, y) : c == 1 ? v(x, y) : 0.0);
      },
      true, top_first);
}

/// zenith's convention: absolute, v down; classic row order (bottom row stored first).
std::string absolute_pfm() { return uv_pfm(kColumns, kRows, true_u, true_v, false); }
/// E&S: offsets from the node's place, v down, bottom row first.
std::string offsets_pfm() { return uv_pfm(kColumns, kRows, offset_u, offset_v, false); }
/// SGCT: absolute, top row first, v counting up from the bottom.
std::string sgct_pfm() {
  return uv_pfm(
      kColumns, kRows, true_u, [](int x, int y) { return 1.0 - true_v(x, y); }, true);
}

/// A warp map read with Catmull–Rom interpolation as `rows` and `conventions` say.
WarpMesh load_as(const std::filesystem::path& file, PfmRowOrder rows, const WarpMapConventions& conventions) {
  return load_pfm_warp_mesh(file, rows, WarpInterpolation::catmull_rom, conventions);
}

void expect_same_nodes(const WarpMesh& a, const WarpMesh& b, double tolerance) {
  ASSERT_EQ(a.columns(), b.columns());
  ASSERT_EQ(a.rows(), b.rows());
  for (int y = 0; y < a.rows(); ++y)
    for (int x = 0; x < a.columns(); ++x) {
      EXPECT_NEAR(a.node(x, y).u, b.node(x, y).u, tolerance) << x << ", " << y;
      EXPECT_NEAR(a.node(x, y).v, b.node(x, y).v, tolerance) << x << ", " << y;
    }
}

/// The largest angle (rad) between the rays of two meshes over one fisheye.
double max_ray_difference_rad(const WarpMesh& a, const WarpMesh& b) {
  auto fisheye = std::make_shared<FisheyeProjection>(256, 256);
  const WarpedProjection wa(192, 144, a, fisheye), wb(192, 144, b, fisheye);
  double worst = 0.0;
  int compared = 0;
  for (double y = 0.5; y < 144; y += 3.7)
    for (double x = 0.5; x < 192; x += 4.3) {
      const auto ra = wa.ray(x, y), rb = wb.ray(x, y);
      EXPECT_EQ(ra.has_value(), rb.has_value()) << x << ", " << y;
      if (!ra || !rb) continue;
      worst = std::max(worst, glm::length(*ra - *rb));
      ++compared;
    }
  EXPECT_GT(compared, 1000);
  return worst;
}

TEST(WarpMapConventions, SourcePointFormulas) {
  // Absolute, v down: as stored.
  WarpSourcePoint p = to_source_point(0.3, 0.2, 1, 5, 3, 4, {});
  EXPECT_DOUBLE_EQ(p.u, 0.3);
  EXPECT_DOUBLE_EQ(p.v, 0.2);
  // Offsets: the node (1 of 5, 3 of 4) sits at (0.25, 1).
  p = to_source_point(0.01, -0.02, 1, 5, 3, 4, {WarpValues::offsets, WarpVDirection::down});
  EXPECT_DOUBLE_EQ(p.u, 0.26);
  EXPECT_DOUBLE_EQ(p.v, 0.98);
  // v up: 1 − v.
  p = to_source_point(0.3, 0.2, 1, 5, 3, 4, {WarpValues::absolute, WarpVDirection::up});
  EXPECT_DOUBLE_EQ(p.v, 0.8);
  // Offsets with v up: the node's own v is 1 − t = 0 (bottom row), an offset of
  // +0.02 upward is 0.02 above the bottom.
  p = to_source_point(0.0, 0.02, 1, 5, 3, 4, {WarpValues::offsets, WarpVDirection::up});
  EXPECT_DOUBLE_EQ(p.u, 0.25);
  EXPECT_NEAR(p.v, 0.98, 1e-15);
  EXPECT_STREQ(to_string(WarpValues::offsets), "offsets");
  EXPECT_STREQ(to_string(WarpVDirection::up), "up");
}

TEST(WarpMapConventions, OffsetMapGivesTheRaysOfItsAbsoluteTwin) {
  ScratchDir dir("conv_offsets");
  LogCapture log;
  const WarpMesh absolute = load_pfm_warp_mesh(dir.write("absolute.pfm", absolute_pfm()));
  const auto offsets_file = dir.write("offsets.pfm", offsets_pfm());
  const WarpMesh offsets =
      load_as(offsets_file, PfmRowOrder::bottom_to_top, {WarpValues::offsets, WarpVDirection::down});
  expect_same_nodes(absolute, offsets, 1e-6);
  EXPECT_NEAR(offsets.node(2, 1).u, 0.25 + 0.04 * std::sin(3.14159265358979 * 0.25) * (1.0 / 6 - 0.5), 1e-7);
  EXPECT_NEAR(offsets.node(2, 1).v, 1.0 / 6 + 0.01 - 0.03 * 0.25 / 6, 1e-7);
  EXPECT_LT(max_ray_difference_rad(absolute, offsets), 1e-6);
  EXPECT_TRUE(log.warnings().empty()) << log.warnings().front();

  // The same offsets read as absolute positions: warned about, naming the file and the fix.
  load_pfm_warp_mesh(offsets_file);
  const std::string warning = log.expect_warning({"offsets.pfm", "look like offsets", "\"values\": \"offsets\""});
  EXPECT_NE(warning.find("u in [-0.02"), std::string::npos) << warning;
}

TEST(WarpMapConventions, AllZeroOffsetsAreTheIdentity) {
  ScratchDir dir("conv_zeros");
  LogCapture log;
  const auto zeros = dir.write("zeros.pfm", make_pfm(
                                                5, 4, 3, [](int, int, int) { return 0.0f; }, true, true));
  const WarpMesh identity = load_pfm_warp_mesh(zeros, PfmRowOrder::top_to_bottom, WarpInterpolation::bilinear,
                                               {WarpValues::offsets, WarpVDirection::down});
  for (const double s : {0.0, 0.13, 0.5, 0.77, 1.0})
    for (const double t : {0.0, 0.31, 0.5, 1.0}) {
      const auto sample = identity.sample(s, t);
      ASSERT_TRUE(sample);
      EXPECT_NEAR(sample->u, s, 1e-12);
      EXPECT_NEAR(sample->v, t, 1e-12);
    }
  auto fisheye = std::make_shared<FisheyeProjection>(64, 64);
  const WarpedProjection warped(64, 64, identity, fisheye);
  for (double y = 0.5; y < 64; y += 5)
    for (double x = 0.5; x < 64; x += 5) {
      const auto expected = fisheye->ray(x, y), actual = warped.ray(x, y);
      ASSERT_EQ(expected.has_value(), actual.has_value());
      if (expected) {
        EXPECT_LT(glm::length(*expected - *actual), 1e-9);
      }
    }
  EXPECT_TRUE(log.warnings().empty());

  // Read as absolute values (the default) every sample maps to (0, 0): warned about.
  const WarpMesh collapsed = load_pfm_warp_mesh(zeros);
  EXPECT_EQ(collapsed.node(3, 2).u, 0.0);
  log.expect_warning({"zeros.pfm", "every valid sample (20) maps to one point (u, v) = (0, 0)", "all zeros",
                      "\"values\": \"offsets\""});
}

TEST(WarpMapConventions, SgctTopFirstVUpMatchesOnceConfiguredAndMirrorsWithTheDefaults) {
  ScratchDir dir("conv_sgct");
  LogCapture log;
  const WarpMesh reference = load_pfm_warp_mesh(dir.write("absolute.pfm", absolute_pfm()));
  // SGCT / E&S surface: the first stored row is the top, v counts up from the bottom.
  const auto sgct = dir.write("sgct.pfm", sgct_pfm());
  const WarpMesh configured = load_as(sgct, PfmRowOrder::top_to_bottom, {WarpValues::absolute, WarpVDirection::up});
  expect_same_nodes(reference, configured, 1e-6);
  EXPECT_LT(max_ray_difference_rad(reference, configured), 1e-6);

  // With the defaults (bottom row first, v down) both flips apply: node (i, j)
  // gets the source point of node (i, rows − 1 − j), mirrored in v.
  const WarpMesh defaults = load_pfm_warp_mesh(sgct);
  for (int y = 0; y < kRows; ++y)
    for (int x = 0; x < kColumns; ++x) {
      EXPECT_NEAR(defaults.node(x, y).u, true_u(x, kRows - 1 - y), 1e-6);
      EXPECT_NEAR(defaults.node(x, y).v, 1.0 - true_v(x, kRows - 1 - y), 1e-6);
    }
  // Only the v direction wrong: the mapping mirrored in v, rows in place.
  const WarpMesh v_wrong = load_pfm_warp_mesh(sgct, PfmRowOrder::top_to_bottom);
  for (int y = 0; y < kRows; ++y)
    for (int x = 0; x < kColumns; ++x) {
      EXPECT_NEAR(v_wrong.node(x, y).u, true_u(x, y), 1e-6);
      EXPECT_NEAR(v_wrong.node(x, y).v, 1.0 - true_v(x, y), 1e-6);
    }
  // Only the row order wrong: rows swapped top for bottom, v in place.
  const WarpMesh rows_wrong = load_as(sgct, PfmRowOrder::bottom_to_top, {WarpValues::absolute, WarpVDirection::up});
  for (int y = 0; y < kRows; ++y)
    for (int x = 0; x < kColumns; ++x) EXPECT_NEAR(rows_wrong.node(x, y).v, true_v(x, kRows - 1 - y), 1e-6);

  // An identity map written v up and read v down shows the source upside down:
  // the ray of (x, y) is the fisheye's at (x, height − y).
  const auto identity_up = dir.write(
      "identity_up.pfm", uv_pfm(
                             3, 3, [](int x, int) { return 0.5 * x; }, [](int, int y) { return 1.0 - 0.5 * y; }, true));
  auto fisheye = std::make_shared<FisheyeProjection>(100, 100);
  const WarpedProjection upside_down(
      100, 100, load_pfm_warp_mesh(identity_up, PfmRowOrder::top_to_bottom, WarpInterpolation::bilinear), fisheye);
  for (double y = 0.5; y < 100; y += 9)
    for (double x = 0.5; x < 100; x += 9) {
      const auto expected = fisheye->ray(x, 100 - y), actual = upside_down.ray(x, y);
      ASSERT_EQ(expected.has_value(), actual.has_value());
      if (expected) {
        EXPECT_LT(glm::length(*expected - *actual), 1e-9) << x << ", " << y;
      }
    }
  EXPECT_TRUE(log.warnings().empty());
}

TEST(WarpMapConventions, WarnsWhenMostSamplesMapOutsideTheSource) {
  ScratchDir dir("conv_outside");
  LogCapture log;
  // An absolute identity map read as offsets: u = 2s, v = 2t, outside for 3/4 of the nodes.
  const auto identity = dir.write(
      "identity.pfm", uv_pfm(
                          5, 5, [](int x, int) { return 0.25 * x; }, [](int, int y) { return 0.25 * y; }, false));
  load_as(identity, PfmRowOrder::bottom_to_top, {WarpValues::offsets, WarpVDirection::down});
  log.expect_warning({"identity.pfm", "16 of 25 valid samples (64 %) map outside the source image", "u in [0, 2]",
                      "read as offsets values, v down", "\"values\""});
  // Plausible maps give no warning: no message from the checks.
  PfmImage map;
  map.width = 2, map.height = 2, map.channels = 3;
  map.samples = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  EXPECT_TRUE(warp_map_warnings(map, {}, "ok.pfm").empty());
  // Half outside is not "most".
  map.samples = {0, 0, 0, 1.5f, 0, 0, 0, 1, 0, 1.5f, 1, 0};
  EXPECT_TRUE(warp_map_warnings(map, {}, "half.pfm").empty());
}

// ---- viewport config keys ---------------------------------------------------------

json pfm_output(const json& warp) {
  json j = json::parse(R"({"zenith_viewports": 1, "name": "t", "outputs": [
    {"name": "a", "size": [192, 144], "projection": {"type": "fisheye"}}]})");
  j["outputs"][0]["warp"] = warp;
  return j;
}

TEST(WarpMapConventions, ViewportKeysSelectTheConventions) {
  ScratchDir dir("conv_viewport");
  dir.write("absolute.pfm", absolute_pfm());
  dir.write("sgct.pfm", sgct_pfm());
  dir.write("es.pfm", offsets_pfm());
  const auto parse = [&](const json& warp) { return parse_viewport_config(pfm_output(warp), "v.json", dir.path()); };
  // A warp the config refuses: the error names each of `parts`.
  const auto expect_warp_error = [&](const json& warp, const std::vector<std::string>& parts) {
    expect_error([&] { parse(warp); }, parts);
  };
  const ViewportConfig plain = parse(json{{"file", "absolute.pfm"}, {"format", "pfm"}});
  EXPECT_EQ(plain.outputs[0].warp->row_order, PfmRowOrder::bottom_to_top);
  EXPECT_EQ(plain.outputs[0].warp->conventions.values, WarpValues::absolute);
  EXPECT_EQ(plain.outputs[0].warp->conventions.v_direction, WarpVDirection::down);
  const ViewportConfig sgct =
      parse(json{{"file", "sgct.pfm"}, {"format", "pfm"}, {"row_order", "top_to_bottom"}, {"v_direction", "up"}});
  EXPECT_EQ(sgct.outputs[0].warp->row_order, PfmRowOrder::top_to_bottom);
  EXPECT_EQ(sgct.outputs[0].warp->conventions.v_direction, WarpVDirection::up);
  const ViewportConfig es = parse(json{{"file", "es.pfm"}, {"format", "pfm"}, {"values", "offsets"}});
  EXPECT_EQ(es.outputs[0].warp->conventions.values, WarpValues::offsets);
  for (const ViewportConfig* other : {&sgct, &es}) {
    double worst = 0.0;
    for (double y = 0.5; y < 144; y += 7.1)
      for (double x = 0.5; x < 192; x += 6.3) {
        const auto a = plain.outputs[0].projection->ray(x, y), b = other->outputs[0].projection->ray(x, y);
        ASSERT_EQ(a.has_value(), b.has_value());
        if (a) worst = std::max(worst, glm::length(*a - *b));
      }
    EXPECT_LT(worst, 1e-6);
  }

  expect_warp_error(json{{"file", "sgct.pfm"}, {"format", "pfm"}, {"row_order", "top_first"}},
                    {"v.json: /outputs/0/warp/row_order", "top_first", "\"bottom_to_top\", \"top_to_bottom\""});
  expect_warp_error(json{{"file", "sgct.pfm"}, {"format", "pfm"}, {"v_direction", "upward"}},
                    {"v.json: /outputs/0/warp/v_direction", "\"down\", \"up\""});
  expect_warp_error(json{{"file", "sgct.pfm"}, {"format", "pfm"}, {"values", "relative"}},
                    {"v.json: /outputs/0/warp/values", "\"absolute\", \"offsets\""});
  dir.write("m.data", "2\n2 2\n-1 -1 0 1 1\n1 -1 1 1 1\n-1 1 0 0 1\n1 1 1 0 1\n");
  expect_warp_error(json{{"file", "m.data"}, {"format", "bourke"}, {"values", "offsets"}},
                    {"v.json: /outputs/0/warp/values", "applies to \"format\": \"pfm\" and \"mpcdi\" only"});
  expect_warp_error(
      json{{"file", "m.data"}, {"format", "bourke"}, {"v_direction", "up"}},
      {"v.json: /outputs/0/warp/v_direction", "applies to \"format\": \"pfm\" only (format is \"bourke\")"});
}

}  // namespace
}  // namespace zenith::warp
