// One broken output must not stop another (ViewportLoadOptions::keep_broken_warps,
// ViewportConfig::require_renderable): the other outputs load and render, the
// broken one gives the error a strict load gives, and an automatically blended
// partner of a broken output says why it cannot be blended.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "core/json_reader.h"
#include "tests/warp/mpcdi_test_support.h"
#include "tests/warp/warp_file_test_support.h"
#include "warp/blending.h"
#include "warp/viewport_config.h"
#include "warp/warped_projection.h"

namespace zenith::warp {
namespace {

using nlohmann::json;
using testing::expect_error;
using testing::make_pfm;
using testing::make_zip;
using testing::ScratchDir;
using testing::valid_2d_members;

float identity(int x, int y, int c) { return static_cast<float>(c == 0 ? x / 2.0 : c == 1 ? y / 2.0 : 0.0); }

/// Outputs "good" (an identity PFM warp) and "bad" (`bad_warp`), blends as given.
json two_outputs(const json& bad_warp, const std::string& good_blend = "none", const std::string& bad_blend = "none") {
  json j = json::parse(R"({"zenith_viewports": 1, "name": "pair", "outputs": [
    {"name": "good", "size": [48, 32], "projection": {"type": "planar", "fov_deg": 60},
     "warp": {"file": "good.pfm", "format": "pfm"}},
    {"name": "bad", "size": [48, 32], "projection": {"type": "planar", "fov_deg": 60, "yaw_deg": 50}}]})");
  j["outputs"][0]["blend"] = good_blend;
  j["outputs"][1]["blend"] = bad_blend;
  j["outputs"][1]["warp"] = bad_warp;
  return j;
}

class BrokenOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_.write("good.pfm", make_pfm(3, 3, 3, identity, true, false));
    std::string truncated = make_pfm(3, 3, 3, identity, true, false);
    truncated.resize(truncated.size() - 4);
    dir_.write("bad.pfm", truncated);
    make_zip(dir_, "show.mpcdi", valid_2d_members());
  }
  ViewportConfig strict(const json& j) const { return parse_viewport_config(j, "pair.json", dir_.path()); }
  ViewportConfig tolerant(const json& j) const {
    return parse_viewport_config(j, "pair.json", dir_.path(), {.keep_broken_warps = true});
  }
  ScratchDir dir_{"broken_output"};
};

TEST_F(BrokenOutput, TheGoodOutputLoadsAndTheBrokenOneGivesTheStrictError) {
  const json j = two_outputs(json{{"file", "bad.pfm"}, {"format", "pfm"}});
  std::string strict_message;
  try {
    strict(j);
    FAIL() << "a strict load accepted the broken warp";
  } catch (const ConfigError& e) {
    strict_message = e.what();
  }
  EXPECT_NE(strict_message.find("pair.json: /outputs/1/warp/file: cannot use the warp: "), std::string::npos);
  EXPECT_NE(strict_message.find("bad.pfm: PFM: truncated"), std::string::npos) << strict_message;

  const ViewportConfig c = tolerant(j);
  ASSERT_EQ(c.outputs.size(), 2u);
  const OutputConfig& good = c.outputs[0];
  const OutputConfig& bad = c.outputs[1];
  EXPECT_FALSE(good.warp_error);
  ASSERT_NE(good.projection, nullptr);
  EXPECT_NE(dynamic_cast<const WarpedProjection*>(good.projection.get()), nullptr);
  EXPECT_TRUE(good.projection->ray(24.0, 16.0).has_value());
  EXPECT_NO_THROW(c.require_renderable(0));
  const BlendMask mask = output_blend_mask(c, 0);
  EXPECT_EQ(mask.width, 48);
  EXPECT_FLOAT_EQ(mask.at(10, 10), 1.0f);

  EXPECT_EQ(bad.projection, nullptr);
  ASSERT_TRUE(bad.warp_error);
  ASSERT_TRUE(bad.warp);
  EXPECT_EQ(bad.warp->format, "pfm");
  try {
    c.require_renderable(1);
    FAIL() << "the broken output was called renderable";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), strict_message);
    EXPECT_EQ(e.key(), "/outputs/1/warp/file");
  }
  expect_error([&] { output_blend_mask(c, 1); }, {strict_message});
}

TEST_F(BrokenOutput, MissingFilesAndUnknownRegionsAreKeptToo) {
  ViewportConfig c = tolerant(two_outputs(json{{"file", "absent.pfm"}, {"format", "pfm"}}));
  expect_error([&] { c.require_renderable(1); }, {"pair.json: /outputs/1/warp/file", "absent.pfm", "file not found"});
  EXPECT_NO_THROW(c.require_renderable(0));
  c = tolerant(two_outputs(json{{"file", "show.mpcdi"}, {"format", "mpcdi"}, {"region", "middle"}}));
  expect_error([&] { c.require_renderable(1); },
               {"pair.json: /outputs/1/warp/region", "\"middle\": no such region", "(regions: \"left\", \"right\")"});
  EXPECT_NO_THROW(c.require_renderable(0));
  // Mistakes in the config's own keys still fail the whole load.
  expect_error(
      [&] {
        tolerant(two_outputs(json{{"file", "bad.pfm"}, {"format", "pfm"}, {"values", "relative"}}));
      },
      {"pair.json: /outputs/1/warp/values", "\"absolute\", \"offsets\""});
  expect_error(
      [&] {
        tolerant(two_outputs(json{{"file", 7}, {"format", "pfm"}}));
      },
      {"pair.json: /outputs/1/warp/file"});
}

TEST_F(BrokenOutput, AnAutomaticBlendPartnerOfABrokenOutputSaysWhy) {
  const ViewportConfig c = tolerant(two_outputs(json{{"file", "bad.pfm"}, {"format", "pfm"}}, "auto", "auto"));
  expect_error([&] { c.require_renderable(0); },
               {"pair.json: /outputs/0/blend: output 'good' blends automatically with output 'bad', whose warp cannot "
                "be used, so its mask cannot be computed: pair.json: /outputs/1/warp/file: cannot use the warp:",
                "bad.pfm: PFM: truncated"});
  expect_error([&] { output_blend_mask(c, 0); }, {"output 'good' blends automatically with output 'bad'"});
  expect_error([&] { const AutoBlend blend(c); }, {"pair.json: /outputs/1/warp/file", "truncated"});
  // Without a blend between them, the good one is independent again.
  EXPECT_NO_THROW(
      tolerant(two_outputs(json{{"file", "bad.pfm"}, {"format", "pfm"}}, "auto", "none")).require_renderable(0));
}

}  // namespace
}  // namespace zenith::warp
