// Viewport configs (warp/viewport_config.h): the example files load and say
// what they claim, malformed configs are rejected with the file, the JSON
// pointer and the reason, warps and blend files are wired in, and the display
// wall's bezel arithmetic.
#include "warp/viewport_config.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/json_reader.h"
#include "core/units.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"
#include "warp/warped_projection.h"
#include "warp_file_test_support.h"

namespace zenith::warp {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::expect_error;
using testing::ScratchDir;

const fs::path kViewports = fs::path(ZENITH_SOURCE_DIR) / "configs" / "viewports";

json minimal() {
  return json::parse(R"({"zenith_viewports": 1, "name": "t", "outputs": [
    {"name": "a", "size": [64, 40], "projection": {"type": "planar", "fov_deg": 60}}]})");
}

ViewportConfig parse(const json& j, const fs::path& base = ".") { return parse_viewport_config(j, "t.json", base); }

TEST(ViewportConfig, EveryExampleLoads) {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(kViewports)) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    SCOPED_TRACE(entry.path().string());
    const ViewportConfig c = load_viewport_config(entry.path());
    EXPECT_FALSE(c.outputs.empty());
    EXPECT_EQ(c.name, entry.path().stem().string());
    for (const OutputConfig& o : c.outputs) {
      ASSERT_NE(o.projection, nullptr);
      EXPECT_EQ(o.projection->width(), o.width_px);
      EXPECT_EQ(o.projection->height(), o.height_px);
    }
  }
  EXPECT_GE(files, 3);
}

TEST(ViewportConfig, DomeMasterIsOne4kFisheye) {
  const ViewportConfig c = load_viewport_config(kViewports / "dome-4k.json");
  ASSERT_EQ(c.outputs.size(), 1u);
  const OutputConfig& o = c.outputs[0];
  EXPECT_EQ(o.width_px, 4096);
  EXPECT_EQ(o.height_px, 4096);
  const auto* f = dynamic_cast<const FisheyeProjection*>(o.projection.get());
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->fov_deg(), 180.0);
  EXPECT_EQ(o.blend.mode, BlendMode::none);
}

TEST(ViewportConfig, SixProjectorDomeHasSixAutoBlendedFrusta) {
  const ViewportConfig c = load_viewport_config(kViewports / "dome-6-projectors.json");
  ASSERT_EQ(c.outputs.size(), 6u);
  for (const OutputConfig& o : c.outputs) {
    EXPECT_EQ(o.width_px, 1920);
    EXPECT_EQ(o.height_px, 1200);
    EXPECT_EQ(o.blend.mode, BlendMode::automatic);
    EXPECT_NE(dynamic_cast<const PlanarProjection*>(o.projection.get()), nullptr);
  }
  EXPECT_EQ(c.index_of("p6-zenith"), 5u);
  EXPECT_EQ(c.find("nope"), nullptr);
  expect_error([&] { (void)c.index_of("nope"); }, {"no output named 'nope'", "p1, p2"});
}

TEST(ViewportConfig, WallFrustaSkipTheBezels) {
  const ViewportConfig c = load_viewport_config(kViewports / "wall-3x2.json");
  ASSERT_EQ(c.outputs.size(), 6u);
  DisplayWall wall;
  wall.columns = 3;
  wall.rows = 2;
  wall.screen_width_mm = 1209.6;
  wall.screen_height_mm = 680.4;
  wall.bezel_mm = 3.5;
  wall.distance_mm = 3000.0;
  for (int row = 0; row < 2; ++row)
    for (int column = 0; column < 3; ++column) {
      const OutputConfig& o = c.outputs[static_cast<std::size_t>(row * 3 + column)];
      SCOPED_TRACE(o.name);
      const auto* p = dynamic_cast<const PlanarProjection*>(o.projection.get());
      ASSERT_NE(p, nullptr);
      const PlanarFrustum want = display_wall_frustum(wall, column, row);
      EXPECT_NEAR(p->frustum().left_deg, want.left_deg, 1e-5);
      EXPECT_NEAR(p->frustum().right_deg, want.right_deg, 1e-5);
      EXPECT_NEAR(p->frustum().down_deg, want.down_deg, 1e-5);
      EXPECT_NEAR(p->frustum().up_deg, want.up_deg, 1e-5);
    }
  // The wall is one plane: a point of the wall (in tangent units x / D) seen
  // by a screen sits where the bezel arithmetic puts it, and the 7 mm between
  // two pictures is seen by neither neighbour.
  const double d = 3000.0, w = 1209.6, gap = 7.0;
  const double x_edge_mm = w / 2 + gap / 2;  // the middle of the gap right of the centre screen
  const glm::dvec3 in_gap(x_edge_mm / d, 0.1, -1.0);
  for (std::size_t i : {1u, 2u}) {
    const auto px = c.outputs[i].projection->pixel(in_gap);
    ASSERT_TRUE(px.has_value());
    EXPECT_TRUE(px->x < 0.0 || px->x > c.outputs[i].width_px) << c.outputs[i].name << " sees the bezel gap";
  }
  // The left edge of the right screen is exactly 7 mm right of the centre screen's right edge.
  const auto right_edge = c.outputs[1].projection->ray(1920.0, 540.0);
  const auto left_edge = c.outputs[2].projection->ray(0.0, 540.0);
  ASSERT_TRUE(right_edge && left_edge);
  const double x1 = right_edge->x / -right_edge->z * d, x2 = left_edge->x / -left_edge->z * d;
  EXPECT_NEAR(x2 - x1, gap, 1e-3);
}

TEST(ViewportConfig, DisplayWallHelperChecksItsInput) {
  DisplayWall wall{3, 2, 1000.0, 500.0, 5.0, 2000.0};
  const PlanarFrustum mid = display_wall_frustum(wall, 1, 0);
  EXPECT_NEAR(mid.left_deg, -mid.right_deg, 1e-12);
  EXPECT_NEAR(std::tan(mid.down_deg * zenith::core::kPi / 180.0) * 2000.0, 5.0,
              1e-9);  // the bottom edge 5 mm above centre
  expect_error([&] { (void)display_wall_frustum(wall, 3, 0); }, {"outside 3 x 2"});
  wall.distance_mm = 0.0;
  expect_error([&] { (void)display_wall_frustum(wall, 0, 0); }, {"distance"});
}

TEST(ViewportConfig, DefaultsAndBlendForms) {
  json j = minimal();
  ViewportConfig c = parse(j);
  EXPECT_EQ(c.outputs[0].blend.mode, BlendMode::none);
  EXPECT_EQ(c.outputs[0].black_level, 0.0);
  EXPECT_EQ(c.outputs[0].warp, std::nullopt);

  j["outputs"][0]["blend"] = "auto";
  j["outputs"][0]["black_level"] = 0.05;
  c = parse(j);
  EXPECT_EQ(c.outputs[0].blend.mode, BlendMode::automatic);
  EXPECT_EQ(c.outputs[0].blend.width_fraction, 0.1);
  EXPECT_EQ(c.outputs[0].black_level, 0.05);

  j["outputs"][0]["blend"] = json::parse(R"({"type": "auto", "width_fraction": 0.2})");
  c = parse(j);
  EXPECT_EQ(c.outputs[0].blend.width_fraction, 0.2);

  ScratchDir dir("viewport_blend");
  dir.write("mask.png", "not read at parse time");
  j["outputs"][0]["blend"] = json::parse(R"({"file": "mask.png", "gamma": 2.2})");
  c = parse(j, dir.path());
  EXPECT_EQ(c.outputs[0].blend.mode, BlendMode::file);
  EXPECT_EQ(c.outputs[0].blend.file, dir.path() / "mask.png");
  EXPECT_EQ(c.outputs[0].blend.gamma, 2.2);
}

TEST(ViewportConfig, WarpFileWrapsTheProjection) {
  ScratchDir dir("viewport_warp");
  // A 3 × 3 PFM warp map: identity (u, v) = (s, t) at the nodes.
  const auto pfm = testing::make_pfm(
      3, 3, 3, [](int x, int y, int c) { return c == 0   ? 0.5f * x
                                                : c == 1 ? 0.5f * y
                                                         : 0.0f; }, true, false);
  dir.write("warp.pfm", pfm);
  json j = minimal();
  j["outputs"][0]["warp"] = json::parse(R"({"file": "warp.pfm", "format": "pfm"})");
  const ViewportConfig c = parse(j, dir.path());
  const auto* warped = dynamic_cast<const WarpedProjection*>(c.outputs[0].projection.get());
  ASSERT_NE(warped, nullptr);
  EXPECT_EQ(warped->width(), 64);
  const auto a = warped->ray(10.5, 20.5);
  const auto b = warped->base().ray(10.5, 20.5);
  ASSERT_TRUE(a && b);
  EXPECT_NEAR(glm::length(*a - *b), 0.0, 1e-9);  // the identity warp shows the base image
  ASSERT_TRUE(c.outputs[0].warp.has_value());
  EXPECT_EQ(c.outputs[0].warp->format, "pfm");

  // A broken warp file: the loader's message, at /outputs/0/warp/file.
  dir.write("bad.pfm", "PF\n3 3\n-1\nshort");
  j["outputs"][0]["warp"]["file"] = "bad.pfm";
  expect_error([&] { parse(j, dir.path()); }, {"t.json: /outputs/0/warp/file", "truncated"});
}

/// One malformed config: `edit` breaks minimal(); the error names the file, the
/// pointer and the reason.
struct Malformed {
  const char* what;
  std::function<void(json&)> edit;
  std::string pointer, reason;
};

TEST(ViewportConfig, MalformedConfigsAreRejectedWithFilePointerAndReason) {
  const std::vector<Malformed> cases = {
      {"no version", [](json& j) { j.erase("zenith_viewports"); }, "/zenith_viewports", "schema version"},
      {"future version", [](json& j) { j["zenith_viewports"] = 2; }, "/zenith_viewports", "must be in [1, 1]"},
      {"unknown top-level key", [](json& j) { j["outputz"] = 1; }, "/outputz", "unknown key"},
      {"no outputs", [](json& j) { j["outputs"] = json::array(); }, "/outputs", "1 to 256 outputs"},
      {"output not an object", [](json& j) { j["outputs"][0] = 3; }, "/outputs/0", "must be an object"},
      {"unknown output key", [](json& j) { j["outputs"][0]["blackLevel"] = 0.1; }, "/outputs/0/blackLevel",
       "unknown key"},
      {"missing size", [](json& j) { j["outputs"][0].erase("size"); }, "/outputs/0/size", "missing required key"},
      {"size not a pair", [](json& j) { j["outputs"][0]["size"] = {64}; }, "/outputs/0/size", "[width, height]"},
      {"size out of range",
       [](json& j) {
         j["outputs"][0]["size"] = {64, 0};
       },
       "/outputs/0/size/1", "= 0: must be in [1, 16384] px"},
      {"size not integer",
       [](json& j) {
         j["outputs"][0]["size"] = {64.5, 40};
       },
       "/outputs/0/size/0", "integer"},
      {"bad name", [](json& j) { j["outputs"][0]["name"] = "a/b"; }, "/outputs/0/name", "letters, digits"},
      {"duplicate name", [](json& j) { j["outputs"].push_back(j["outputs"][0]); }, "/outputs/1/name",
       "duplicate output name"},
      {"projection out of range", [](json& j) { j["outputs"][0]["projection"]["fov_deg"] = 200; },
       "/outputs/0/projection/fov_deg", "200"},
      {"projection missing", [](json& j) { j["outputs"][0].erase("projection"); }, "/outputs/0/projection",
       "missing required key"},
      {"black level too high", [](json& j) { j["outputs"][0]["black_level"] = 0.8; }, "/outputs/0/black_level",
       "= 0.8: must be in [0, 0.5]"},
      {"black level negative", [](json& j) { j["outputs"][0]["black_level"] = -0.1; }, "/outputs/0/black_level",
       "must be in [0, 0.5]"},
      {"unknown blend word", [](json& j) { j["outputs"][0]["blend"] = "smooth"; }, "/outputs/0/blend",
       "must be one of \"none\", \"auto\""},
      {"blend width out of range",
       [](json& j) { j["outputs"][0]["blend"] = json::parse(R"({"type": "auto", "width_fraction": 0.9})"); },
       "/outputs/0/blend/width_fraction", "must be in [0.001, 0.5]"},
      {"blend file missing", [](json& j) { j["outputs"][0]["blend"] = json::parse(R"({"file": "nowhere.png"})"); },
       "/outputs/0/blend/file", "no such file"},
      {"blend gamma out of range",
       [](json& j) { j["outputs"][0]["blend"] = json::parse(R"({"file": "x.png", "gamma": 0})"); },
       "/outputs/0/blend/file", "no such file"},  // the file is checked first
      {"blend key for the wrong type",
       [](json& j) { j["outputs"][0]["blend"] = json::parse(R"({"type": "auto", "gamma": 2})"); },
       "/outputs/0/blend/gamma", "unknown key"},
      {"warp format unknown",
       [](json& j) { j["outputs"][0]["warp"] = json::parse(R"({"file": "w.data", "format": "obj"})"); },
       "/outputs/0/warp/format", "must be one of \"bourke\", \"pfm\", \"mpcdi\""},
      {"warp file missing",
       [](json& j) { j["outputs"][0]["warp"] = json::parse(R"({"file": "w.data", "format": "bourke"})"); },
       "/outputs/0/warp/file", "no such file"},
      {"warp not an object", [](json& j) { j["outputs"][0]["warp"] = "w.data"; }, "/outputs/0/warp",
       "must be an object"},
  };
  for (const Malformed& m : cases) {
    SCOPED_TRACE(m.what);
    json j = minimal();
    m.edit(j);
    testing::expect_config_error([&] { parse(j, fs::temp_directory_path()); }, "t.json", m.pointer, m.reason);
  }
  EXPECT_GE(cases.size(), 10u);
}

TEST(ViewportConfig, MalformedFilesNameTheFile) {
  ScratchDir dir("viewport_files");
  const fs::path broken = dir.write("broken.json", "{\"zenith_viewports\": 1, ");
  expect_error([&] { load_viewport_config(broken); }, {"broken.json", "not valid JSON"});
  expect_error([&] { load_viewport_config(dir.path() / "absent.json"); }, {"absent.json", "cannot open file"});
  // An MPCDI warp needs its region; a region on a Bourke warp is refused.
  dir.write("w.data", "2\n2 2\n-1 -1 0 0 1\n1 -1 1 0 1\n-1 1 0 1 1\n1 1 1 1 1\n");
  json j = minimal();
  j["outputs"][0]["warp"] = json::parse(R"({"file": "w.data", "format": "bourke", "region": "r1"})");
  expect_error([&] { parse(j, dir.path()); }, {"t.json: /outputs/0/warp/region", "applies to \"format\": \"mpcdi\""});
  j["outputs"][0]["warp"].erase("region");
  EXPECT_NE(dynamic_cast<const WarpedProjection*>(parse(j, dir.path()).outputs[0].projection.get()), nullptr);
  j["outputs"][0]["warp"] = json::parse(R"({"file": "w.data", "format": "mpcdi"})");
  expect_error([&] { parse(j, dir.path()); }, {"t.json: /outputs/0/warp/region", "missing required key"});
}

}  // namespace
}  // namespace zenith::warp
