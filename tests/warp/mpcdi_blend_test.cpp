// An MPCDI region's alpha and beta maps as its output's α and β:
// "blend": {"type": "mpcdi"} (and its default), the maps placed on the
// output's pixels as OpenGL UV mapping does (warp/mpcdi_blend.h), the output
// stage α·L·(1 − β) + β on the CPU path, two projectors' complementary maps,
// and the refusals. Archives are written here (libzip, libpng).
#include "warp/mpcdi_blend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/warp/mpcdi_test_support.h"
#include "tests/warp/warp_file_test_support.h"
#include "warp/blending.h"
#include "warp/viewport_config.h"

namespace zenith::warp {
namespace {

using nlohmann::json;
using testing::descriptor_with_maps;
using testing::expect_config_error;
using testing::expect_error;
using testing::identity_warp;
using testing::make_grey_png;
using testing::make_zip;
using testing::map_element;
using testing::ScratchDir;

// The ramp archive: a 5 × 3 16-bit alpha map with gammaEmbedded 2 and a 4 × 3
// 8-bit beta map, on a 20 × 9 output (maps smaller than the output, of
// different sizes, as VESA MPCDI v2.0 §3.7 allows).
constexpr int kWidth = 20, kHeight = 9;
constexpr int kAlphaWidth = 5, kAlphaHeight = 3, kBetaWidth = 4, kBetaHeight = 3;
constexpr double kGammaEmbedded = 2.0;

std::uint16_t alpha_stored(int i, int j) {
  return static_cast<std::uint16_t>(std::lround(65535.0 * (0.3 + 0.15 * i - 0.1 * j)));
}
unsigned char beta_stored(int i, int j) { return static_cast<unsigned char>(10 + 9 * i + 20 * j); }  // β ≤ 0.3

/// The alpha map's linear weight of sample (i, j): (stored / 65535)^γ.
double alpha_linear(int i, int j) { return std::pow(alpha_stored(i, j) / 65535.0, kGammaEmbedded); }
double beta_linear(int i, int j) { return beta_stored(i, j) / 255.0; }

/// The ramp's values at the centre of output pixel (x, y) (testing::tent_sum).
double alpha_at(int x, int y) {
  return testing::tent_sum(alpha_linear, kAlphaWidth, kAlphaHeight, kWidth, kHeight, x, y);
}
double beta_at(int x, int y) { return testing::tent_sum(beta_linear, kBetaWidth, kBetaHeight, kWidth, kHeight, x, y); }

std::string ramp_descriptor(const std::string& alpha_element, const std::string& beta_element) {
  return descriptor_with_maps({{"p", kWidth, kHeight, alpha_element + beta_element}});
}

testing::Members ramp_members() {
  const std::vector<std::uint16_t> alpha = testing::map_samples(kAlphaWidth, kAlphaHeight, alpha_stored);
  const std::vector<unsigned char> beta = testing::map_samples(kBetaWidth, kBetaHeight, beta_stored);
  return {{"mpcdi.xml", ramp_descriptor(map_element("alphaMap", "a.png", 1, 16, kGammaEmbedded),
                                        map_element("betaMap", "b.png", 1, 8))},
          {"p.pfm", identity_warp()},
          {"a.png", make_grey_png(kAlphaWidth, kAlphaHeight, alpha)},
          {"b.png", make_grey_png(kBetaWidth, kBetaHeight, beta)}};
}

/// A config of one output showing region "p" of `archive`; `extra` adds keys.
json ramp_config(const std::string& archive, const json& extra = json::object()) {
  json output = {{"name", "p"},
                 {"size", {kWidth, kHeight}},
                 {"projection", {{"type", "planar"}, {"fov_deg", 60}}},
                 {"warp", {{"file", archive}, {"format", "mpcdi"}, {"region", "p"}}}};
  output.update(extra);
  return {{"zenith_viewports", 1}, {"name", "t"}, {"outputs", json::array({output})}};
}

/// The 1-based line of the first `tag` in `text`.
int line_of(const std::string& text, const std::string& tag) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(text.find(tag)), '\n'));
}

TEST(MpcdiMaps, ALowResolutionRampAndBetaMapGiveAlphaLTimesOneMinusBetaPlusBeta) {
  ScratchDir dir("mpcdi_maps");
  make_zip(dir, "ramp.mpcdi", ramp_members());
  const ViewportConfig config =
      parse_viewport_config(ramp_config("ramp.mpcdi", {{"blend", {{"type", "mpcdi"}}}}), "t.json", dir.path());
  const OutputConfig& o = config.outputs[0];
  EXPECT_EQ(o.blend.mode, BlendMode::mpcdi);
  EXPECT_EQ(o.black_level, 0.0);
  EXPECT_EQ(describe_blend(o),
            "mpcdi (region \"p\": alpha map 5x3 px, gammaEmbedded 2; beta map 4x3 px); black level: the beta map");
  const BlendMask mask = output_blend_mask(config, 0);
  ASSERT_EQ(mask.alpha.size(), std::size_t{kWidth * kHeight});
  ASSERT_EQ(mask.beta.size(), std::size_t{kWidth * kHeight});
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      EXPECT_NEAR(mask.at(x, y), alpha_at(x, y), 1e-6) << x << ", " << y;
      EXPECT_NEAR(mask.black_level_at(x, y, 0.0), beta_at(x, y), 1e-6);
    }
  // By hand: pixel (9, 4) reads the alpha map at s = 9.5 / 20 · 5 − 0.5 = 1.875,
  // t = 4.5 / 9 · 3 − 0.5 = 1: 0.125 · (22937 / 65535)² + 0.875 · (32768 / 65535)²
  // = 0.125 · 0.122497 + 0.875 · 0.250008 = 0.234069; the corner pixel the
  // corner sample (clamped): (19661 / 65535)² = 0.0900046.
  EXPECT_NEAR(mask.at(9, 4), 0.234069, 2e-6);
  EXPECT_NEAR(mask.at(0, 0), 0.0900046, 1e-6);
  // β at (9, 4): s = 9.5 / 20 · 4 − 0.5 = 1.4, t = 1: 0.6 · 39 / 255 + 0.4 · 48 / 255 = 0.167059.
  EXPECT_NEAR(mask.black_level_at(9, 4, 0.0), 0.167059, 1e-6);

  // The output stage on the CPU path: P' = α · L · (1 − β) + β per channel.
  std::vector<float> rgb;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c) rgb.push_back(static_cast<float>((x + 2 * y + c + 1) / 60.0));
  const std::vector<float> linear = rgb;
  apply_blend(rgb, 0, kHeight, mask, 0.0);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const double a = alpha_at(x, y);
      const double b = beta_at(x, y);
      for (int c = 0; c < 3; ++c) {
        const std::size_t k = (static_cast<std::size_t>(y) * kWidth + x) * 3 + c;
        EXPECT_NEAR(rgb[k], a * linear[k] * (1.0 - b) + b, 1e-6);
      }
    }
  // The black-level map an export writes is the beta map's.
  EXPECT_EQ(black_level_map(o, mask), mask.beta);
}

TEST(MpcdiMaps, AMapOfTheOutputsSizeIsReadSampleForSample) {
  MpcdiBlendMap map;
  map.gamma_embedded = 2.2;
  map.image = {3, 2, 1, 16, {0.0f, 0.25f, 0.5f, 0.75f, 1.0f, 0.125f}};
  const std::vector<float> same = sample_mpcdi_blend_map(map, 3, 2);
  for (int k = 0; k < 6; ++k)
    EXPECT_FLOAT_EQ(same[static_cast<std::size_t>(k)], static_cast<float>(std::pow(map.image.values[k], 2.2)));
  // Twice the size: each output pixel a quarter of the way between samples (or clamped at the border).
  const std::vector<float> twice = sample_mpcdi_blend_map(map, 6, 4);
  EXPECT_FLOAT_EQ(twice[0], 0.0f);                          // clamped to sample (0, 0)
  EXPECT_NEAR(twice[1], 0.25 * std::pow(0.25, 2.2), 1e-7);  // row 0 clamped (t = 0), s = 0.25
  // Row 1, t = 0.25: 0.75 · 0.25 · 0.25^2.2 + 0.25 · 0.75 · 0.75^2.2 + 0.25 · 0.25 · 1 = 0.170953.
  EXPECT_NEAR(twice[6 + 1], 0.1875 * (std::pow(0.25, 2.2) + std::pow(0.75, 2.2)) + 0.0625, 1e-7);
  EXPECT_NEAR(twice[6 + 1], 0.170953, 1e-6);
  EXPECT_NEAR(twice[2 * 6 + 5], 0.75 * std::pow(0.125, 2.2) + 0.25 * std::pow(0.5, 2.2), 1e-7);  // s clamped, t = 0.75
}

TEST(MpcdiMaps, TwoOverlappingProjectorsMapsSumToOneAcrossTheOverlap) {
  // Two projectors on one plane at unit distance, x from −1 to 1 over 40 px
  // (0.05 a pixel), y from −0.25 to 0.25 over 10: "a" shows pixels 0 to 23,
  // "b" pixels 16 to 39, so 8 columns overlap and pixel x of "a" is pixel
  // x − 16 of "b". Their 12 × 5 alpha maps (a sample every 2 px, at the
  // pixels' positions 1, 3, ..., 23) cross-fade linearly from "a"'s pixel 17
  // to 23: 1, 2/3, 1/3, 0 and 0, 1/3, 2/3, 1 (16-bit 65535 = 3 · 21845).
  ScratchDir dir("mpcdi_maps_pair");
  const auto map_png = [](const std::vector<std::uint16_t>& columns) {
    std::vector<std::uint16_t> v;
    for (int j = 0; j < 5; ++j) v.insert(v.end(), columns.begin(), columns.end());
    return make_grey_png(12, 5, v);
  };
  const std::vector<std::uint16_t> a = {65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 43690, 21845, 0};
  const std::vector<std::uint16_t> b = {0, 21845, 43690, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535};
  make_zip(dir, "pair.mpcdi",
           {{"mpcdi.xml", descriptor_with_maps({{"a", 24, 10, map_element("alphaMap", "a.png", 1, 16, 1.0)},
                                                {"b", 24, 10, map_element("alphaMap", "b.png", 1, 16, 1.0)}})},
            {"a.pfm", identity_warp()},
            {"b.pfm", identity_warp()},
            {"a.png", map_png(a)},
            {"b.png", map_png(b)}});
  const double deg = 180.0 / std::acos(-1.0), up = std::atan(0.25) * deg;
  const auto output = [&](const char* name, double left, double right) {
    return json{{"name", name},
                {"size", {24, 10}},
                {"projection",
                 {{"type", "planar"},
                  {"left_deg", std::atan(left) * deg},
                  {"right_deg", std::atan(right) * deg},
                  {"down_deg", -up},
                  {"up_deg", up}}},
                {"warp", {{"file", "pair.mpcdi"}, {"format", "mpcdi"}, {"region", name}}}};
  };
  const ViewportConfig config = parse_viewport_config(
      {{"zenith_viewports", 1}, {"name", "pair"}, {"outputs", {output("a", -1.0, 0.2), output("b", -0.2, 1.0)}}},
      "pair.json", dir.path());
  ASSERT_EQ(config.outputs[0].blend.mode, BlendMode::mpcdi);  // the default for a region with an alpha map
  const BlendMask mask_a = output_blend_mask(config, 0), mask_b = output_blend_mask(config, 1);
  const Projection& pa = *config.outputs[0].projection;
  const Projection& pb = *config.outputs[1].projection;
  int overlap = 0;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 24; ++x) {
      const std::optional<glm::dvec3> d = pa.ray(x + 0.5, y + 0.5);
      ASSERT_TRUE(d);
      const std::optional<glm::dvec2> in_b = pb.pixel(*d);
      if (x < 16) {  // "a" alone: its full light
        EXPECT_EQ(mask_a.at(x, y), 1.0f) << x;
        continue;
      }
      ASSERT_TRUE(in_b) << x;
      const int xb = static_cast<int>(std::floor(in_b->x)), yb = static_cast<int>(std::floor(in_b->y));
      EXPECT_EQ(xb, x - 16);
      EXPECT_EQ(yb, y);
      EXPECT_NEAR(in_b->x, xb + 0.5, 1e-6);
      // Both projectors light this direction: their light sums to the picture's, L = 0.7.
      const double light =
          blend_display_value(0.7, mask_a.at(x, y), 0.0) + blend_display_value(0.7, mask_b.at(xb, yb), 0.0);
      EXPECT_NEAR(light, 0.7, 1e-6) << x;
      EXPECT_NEAR(mask_a.at(x, y) + mask_b.at(xb, yb), 1.0, 1e-6) << x;
      ++overlap;
    }
  EXPECT_EQ(overlap, 8 * 10);
  for (int y = 0; y < 10; ++y)
    for (int xb = 8; xb < 24; ++xb) EXPECT_EQ(mask_b.at(xb, y), 1.0f);  // "b" alone
  // Not a trivial pair: across the overlap "a"'s weight falls from 1 (pixel 16) by 1/6 a pixel
  // from 11/12 (pixel 17) to 1/12 (pixel 22), then 0 (pixel 23, its clamped last sample).
  for (int x = 17; x <= 22; ++x) EXPECT_NEAR(mask_a.at(x, 0), (11.0 - 2.0 * (x - 17)) / 12.0, 1e-6) << x;
  EXPECT_EQ(mask_a.at(16, 0), 1.0f);
  EXPECT_EQ(mask_a.at(23, 0), 0.0f);
}

TEST(MpcdiMaps, TheMapsAreTheDefaultAndAnExplicitBlendKeepsItsMeaning) {
  ScratchDir dir("mpcdi_maps_default");
  make_zip(dir, "ramp.mpcdi", ramp_members());
  const ViewportConfig explicit_maps =
      parse_viewport_config(ramp_config("ramp.mpcdi", {{"blend", "mpcdi"}}), "t.json", dir.path());
  const ViewportConfig by_default = parse_viewport_config(ramp_config("ramp.mpcdi"), "t.json", dir.path());
  EXPECT_EQ(by_default.outputs[0].blend.mode, BlendMode::mpcdi);
  const BlendMask a = output_blend_mask(explicit_maps, 0), b = output_blend_mask(by_default, 0);
  EXPECT_EQ(a.alpha, b.alpha);
  EXPECT_EQ(a.beta, b.beta);

  // "none" with a black level: α = 1, β the number, the maps unused, as before.
  const ViewportConfig none =
      parse_viewport_config(ramp_config("ramp.mpcdi", {{"blend", "none"}, {"black_level", 0.1}}), "t.json", dir.path());
  EXPECT_EQ(none.outputs[0].blend.mode, BlendMode::none);
  EXPECT_FALSE(none.outputs[0].blend.alpha_map);
  const BlendMask n = output_blend_mask(none, 0);
  EXPECT_TRUE(n.beta.empty());
  EXPECT_TRUE(std::all_of(n.alpha.begin(), n.alpha.end(), [](float v) { return v == 1.0f; }));
  std::vector<float> rgb(std::size_t{kWidth * kHeight * 3}, 0.5f);
  apply_blend(rgb, 0, kHeight, n, none.outputs[0].black_level);
  EXPECT_FLOAT_EQ(rgb[0], static_cast<float>(0.5 * 0.9 + 0.1));
  // "auto" keeps its number too.
  const ViewportConfig automatic = parse_viewport_config(
      ramp_config("ramp.mpcdi", {{"blend", "auto"}, {"black_level", 0.05}}), "t.json", dir.path());
  EXPECT_EQ(automatic.outputs[0].blend.mode, BlendMode::automatic);
  EXPECT_EQ(automatic.outputs[0].black_level, 0.05);
  EXPECT_TRUE(output_blend_mask(automatic, 0).beta.empty());

  // An alpha map without a beta map: β is black_level, which may then be given.
  testing::Members alpha_only = ramp_members();
  alpha_only[0].second = ramp_descriptor(map_element("alphaMap", "a.png", 1, 16, kGammaEmbedded), "");
  make_zip(dir, "alpha.mpcdi", alpha_only);
  const ViewportConfig alpha =
      parse_viewport_config(ramp_config("alpha.mpcdi", {{"black_level", 0.02}}), "t.json", dir.path());
  EXPECT_EQ(alpha.outputs[0].blend.mode, BlendMode::mpcdi);
  EXPECT_FALSE(alpha.outputs[0].blend.beta_map);
  const BlendMask m = output_blend_mask(alpha, 0);
  EXPECT_TRUE(m.beta.empty());
  EXPECT_EQ(m.alpha, a.alpha);
  EXPECT_EQ(black_level_map(alpha.outputs[0], m), std::vector<float>(std::size_t{kWidth * kHeight}, 0.02f));

  // A region without an alpha map: blend "none" as before.
  make_zip(dir, "show.mpcdi", testing::valid_2d_members());
  json right = ramp_config("show.mpcdi");
  right["outputs"][0]["warp"]["region"] = "right";
  EXPECT_EQ(parse_viewport_config(right, "t.json", dir.path()).outputs[0].blend.mode, BlendMode::none);
}

TEST(MpcdiMaps, ConfigRefusalsNameTheFileTheOutputAndTheKey) {
  ScratchDir dir("mpcdi_maps_refusals");
  make_zip(dir, "ramp.mpcdi", ramp_members());
  make_zip(dir, "show.mpcdi", testing::valid_2d_members());
  // No MPCDI warp.
  json planar = ramp_config("ramp.mpcdi", {{"blend", {{"type", "mpcdi"}}}});
  planar["outputs"][0].erase("warp");
  expect_config_error([&] { parse_viewport_config(planar, "t.json", dir.path()); }, "t.json", "/outputs/0/blend",
                      "output 'p' has no MPCDI warp");
  // A region without an alpha map.
  json right = ramp_config("show.mpcdi", {{"blend", {{"type", "mpcdi"}}}});
  right["outputs"][0]["warp"]["region"] = "right";
  expect_config_error(
      [&] { parse_viewport_config(right, "t.json", dir.path()); }, "t.json", "/outputs/0/blend",
      "output 'p': region \"right\" of " + (dir.path() / "show.mpcdi").string() + ":mpcdi.xml has no alpha map");
  // A number beside the beta map, given or by default.
  for (const json& blend : {json("mpcdi"), json()}) {
    json both = ramp_config("ramp.mpcdi", {{"black_level", 0.1}});
    if (!blend.is_null()) both["outputs"][0]["blend"] = blend;
    expect_config_error([&] { parse_viewport_config(both, "t.json", dir.path()); }, "t.json", "/outputs/0/black_level",
                        "has a beta map, which gives β per pixel");
  }
  // "mpcdi" takes no other key.
  expect_config_error(
      [&] {
        parse_viewport_config(ramp_config("ramp.mpcdi", {{"blend", {{"type", "mpcdi"}, {"gamma", 2.2}}}}), "t.json",
                              dir.path());
      },
      "t.json", "/outputs/0/blend/gamma", "");
}

TEST(MpcdiMaps, MapsTheSpecOrZenithCannotUseAreRefusedNamingTheArchiveRegionAndElement) {
  ScratchDir dir("mpcdi_maps_bad");
  const auto with = [&](const std::string& name, const std::string& alpha_element, const std::string& png) {
    testing::Members members = ramp_members();
    members[0].second = ramp_descriptor(alpha_element, "");
    members[2].second = png;
    return make_zip(dir, name, members);
  };
  const std::string grey_2x2 = make_grey_png(2, 2, std::vector<unsigned char>{0, 85, 170, 255});
  struct Case {
    std::string name, element, png, message;
  };
  const std::vector<Case> cases = {
      {"tiny.mpcdi", map_element("alphaMap", "a.png", 1, 8, 1.0), make_grey_png(1, 1, std::vector<unsigned char>{255}),
       "is 1x1 px: MPCDI blend maps must be at least 2x2 px"},
      {"depth.mpcdi", map_element("alphaMap", "a.png", 3, 8, 1.0), grey_2x2,
       "declares componentDepth 3, and its PNG has 1 channel (grey)"},
      {"bits.mpcdi", map_element("alphaMap", "a.png", 1, 16, 1.0), grey_2x2,
       "declares bitDepth 16, and its PNG has 8 bits a channel"}};
  for (const Case& c : cases) {
    const std::filesystem::path archive = with(c.name, c.element, c.png);
    const std::string xml = ramp_descriptor(c.element, "");
    const std::string where = archive.string() + ":mpcdi.xml:" + std::to_string(line_of(xml, "<alphaMap>")) + ":";
    expect_error([&] { load_mpcdi(archive); }, {where, "region 'p': alpha map 'a.png'", c.message});
    // The config names its file and key, and carries the loader's message.
    expect_config_error([&] { parse_viewport_config(ramp_config(c.name), "t.json", dir.path()); }, "t.json",
                        "/outputs/0/warp/file", c.message);
  }

  // RGB: grey written as RGB is read as grey; different channels are refused.
  const std::vector<unsigned char> grey_rgb = {0, 0, 0, 85, 85, 85, 170, 170, 170, 255, 255, 255};
  const std::vector<unsigned char> colour_rgb = {0, 0, 0, 85, 85, 85, 170, 100, 170, 255, 255, 255};  // (0, 1) differs
  with("grey_rgb.mpcdi", map_element("alphaMap", "a.png", 3, 8, 1.0), testing::make_rgb_png(2, 2, grey_rgb));
  with("grey.mpcdi", map_element("alphaMap", "a.png", 1, 8, 1.0), grey_2x2);
  const ViewportConfig rgb = parse_viewport_config(ramp_config("grey_rgb.mpcdi"), "t.json", dir.path());
  const ViewportConfig grey = parse_viewport_config(ramp_config("grey.mpcdi"), "t.json", dir.path());
  EXPECT_EQ(output_blend_mask(rgb, 0).alpha, output_blend_mask(grey, 0).alpha);
  const std::filesystem::path colour =
      with("colour.mpcdi", map_element("alphaMap", "a.png", 3, 8, 1.0), testing::make_rgb_png(2, 2, colour_rgb));
  const std::string xml = ramp_descriptor(map_element("alphaMap", "a.png", 3, 8, 1.0), "");
  for (const json& blend : {json("mpcdi"), json()}) {
    json config = ramp_config("colour.mpcdi");
    if (!blend.is_null()) config["outputs"][0]["blend"] = blend;
    expect_config_error([&] { parse_viewport_config(config, "t.json", dir.path()); }, "t.json", "/outputs/0/blend",
                        "output 'p': " + colour.string() + ":mpcdi.xml:" + std::to_string(line_of(xml, "<alphaMap>")) +
                            ": region 'p': alpha map 'a.png' is RGB with channels that differ (pixel (0, 1)");
  }
  // ... and loads with another blend, which does not use the map.
  EXPECT_EQ(parse_viewport_config(ramp_config("colour.mpcdi", {{"blend", "none"}}), "t.json", dir.path())
                .outputs[0]
                .blend.mode,
            BlendMode::none);
}

}  // namespace
}  // namespace zenith::warp
