// MPCDI colour profiles: the .cube reader (warp/cube_lut.h), the
// three stages of VESA MPCDI v2.0 §2.5 (warp/colour_profile.h) against their
// closed forms, and <color> with its LUTs read from archives of each profile
// (warp/mpcdi.h), every refusal naming the file, the line and the field.
// LUTs are written here by generators; nothing is downloaded.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tests/warp/mpcdi_test_support.h"
#include "tests/warp/warp_file_test_support.h"
#include "warp/colour_profile.h"
#include "warp/cube_lut.h"
#include "warp/mpcdi.h"
#include "warp/viewport_config.h"

namespace zenith::warp {
namespace {

using nlohmann::json;
using testing::expect_error;
using testing::make_pfm;
using testing::Members;
using testing::ScratchDir;
using Rgb = std::array<double, 3>;

// ---- generators ---------------------------------------------------------------

/// A 1D .cube of n entries, entry i = f(i / (n − 1)) per channel.
std::string cube_1d(int n, const std::function<Rgb(double)>& f, const std::string& header = "") {
  std::string text = header + fmt::format("LUT_1D_SIZE {}\n", n);
  for (int i = 0; i < n; ++i) {
    const Rgb v = f(static_cast<double>(i) / (n - 1));
    text += fmt::format("{:.9g} {:.9g} {:.9g}\n", v[0], v[1], v[2]);
  }
  return text;
}

/// A 3D .cube of n³ points, red fastest: point (r, g, b) = f(r, g, b) / (n − 1).
std::string cube_3d(int n, const std::function<Rgb(const Rgb&)>& f, const std::string& header = "") {
  std::string text = header + fmt::format("LUT_3D_SIZE {}\n", n);
  for (int b = 0; b < n; ++b)
    for (int g = 0; g < n; ++g)
      for (int r = 0; r < n; ++r) {
        const double s = n - 1;
        const Rgb v = f({r / s, g / s, b / s});
        text += fmt::format("{:.9g} {:.9g} {:.9g}\n", v[0], v[1], v[2]);
      }
  return text;
}

/// A matrix with row sums below 1 (a correction that keeps white within 100 %, §2.5.1.2.2).
constexpr std::array<Rgb, 3> kMatrix = {{{0.80, 0.15, 0.03}, {0.05, 0.90, 0.02}, {0.02, 0.08, 0.85}}};
Rgb times_matrix(const Rgb& v) {
  Rgb out{};
  for (std::size_t i = 0; i < 3; ++i) out[i] = kMatrix[i][0] * v[0] + kMatrix[i][1] * v[1] + kMatrix[i][2] * v[2];
  return out;
}

// ---- the .cube reader -----------------------------------------------------------

TEST(CubeLut, Reads1dAnd3dWithCommentsTitleAndDomain) {
  const std::string one_d = cube_1d(
      5,
      [](double x) {
        return Rgb{x, x * x, 1.0 - x};
      },
      "# written by a test\r\nTITLE \"projector 1\"\r\n\r\nDOMAIN_MIN 0 0 0\r\n"
      "DOMAIN_MAX 1 1 1\r\n");
  const CubeLut a = parse_cube_lut(one_d, "a.cube");
  EXPECT_FALSE(a.is_3d());
  EXPECT_EQ(a.title, "projector 1");
  EXPECT_EQ(a.size, 5);
  ASSERT_EQ(a.rgb.size(), 15u);
  EXPECT_FLOAT_EQ(a.rgb[3 * 2 + 1], 0.25f);  // entry 2, green: 0.5²
  // Between entries 1 and 2 (x = 0.25 .. 0.5), green interpolates 0.0625 .. 0.25 linearly.
  EXPECT_NEAR(a.apply({0.375, 0.375, 0.375})[1], 0.5 * (0.0625 + 0.25), 1e-7);
  EXPECT_NEAR(a.apply({2.0, -1.0, 0.0})[0], 1.0, 1e-7);  // clamped input
  EXPECT_NEAR(a.apply({2.0, -1.0, 0.0})[1], 0.0, 1e-7);

  std::string three_d = cube_3d(
      2,
      [](const Rgb& v) {
        return Rgb{v[0], v[1], v[2]};
      },
      "TITLE \"id\"\n# a comment\nLUT_3D_INPUT_RANGE 0 1\n");
  three_d.append("# a comment after the rows\n");
  const CubeLut b = parse_cube_lut(three_d, "b.cube");
  EXPECT_TRUE(b.is_3d());
  EXPECT_EQ(b.size, 2);
  EXPECT_EQ(b.rgb.size(), 24u);
  // Red fastest: point (1, 0, 0) is the second row.
  EXPECT_EQ(b.rgb[3], 1.0f);
  EXPECT_EQ(b.rgb[4], 0.0f);
  // format_cube_lut writes what parse reads.
  const CubeLut c = parse_cube_lut(format_cube_lut(a), "c.cube");
  EXPECT_EQ(c.title, a.title);
  EXPECT_EQ(c.rgb, a.rgb);
}

TEST(CubeLut, EveryRefusalNamesTheFileLineAndField) {
  const auto refuse = [](const std::string& text, const std::vector<std::string>& parts) {
    expect_error([&] { parse_cube_lut(text, "show.mpcdi:lut.cube"); }, parts);
  };
  refuse("LUT_1D_SIZE 2\n0 0 0\n1 1 1\n", {"show.mpcdi:lut.cube:1:", "LUT_1D_SIZE 2", "[4, 65536]"});
  refuse("LUT_1D_SIZE 65537\n", {"lut.cube:1:", "LUT_1D_SIZE 65537", "[4, 65536]"});
  refuse("LUT_1D_SIZE 4.5\n", {"lut.cube:1:", "must be an integer"});
  refuse("LUT_3D_SIZE 1\n0 0 0\n", {"lut.cube:1:", "LUT_3D_SIZE 1", "[2, 256]"});
  refuse("LUT_1D_SIZE 4\n0 0 0\n0.3 0.3 0.3\n0.6 0.6 0.6\n",
         {"lut.cube:4:", "3 rows of data", "LUT_1D_SIZE 4 needs 4"});
  refuse("LUT_1D_SIZE 4\n0 0 0\n0.3 0.3 0.3\n0.6 0.6 0.6\n1 1 1\n1 1 1\n", {"lut.cube:6:", "more than the 4 rows"});
  refuse("LUT_1D_SIZE 4\n0 0 0\n0.3 x 0.3\n", {"lut.cube:3:", "row 2", "green value 'x' is not a finite number"});
  refuse("LUT_1D_SIZE 4\n0 0 0\n0.3 0.3\n", {"lut.cube:3:", "row 2", "2 values, must be 3"});
  refuse("LUT_1D_SIZE 4\n0 0 0\n0.3 0.3 nan\n", {"lut.cube:3:", "blue value 'nan'"});
  refuse("DOMAIN_MAX 2 2 2\nLUT_1D_SIZE 4\n", {"lut.cube:1:", "DOMAIN_MAX value 1 = 2", "reserved for HDR"});
  refuse("DOMAIN_MIN 0 -0.5 0\n", {"lut.cube:1:", "DOMAIN_MIN value 2 = -0.5", "must be 0"});
  refuse("LUT_3D_INPUT_RANGE 0 4\n", {"lut.cube:1:", "LUT_3D_INPUT_RANGE max", "reserved for HDR"});
  refuse("DOMAIN_MAX 1 one 1\n", {"lut.cube:1:", "DOMAIN_MAX value 2 'one' is not a number"});
  refuse("LUT_1D_SIZE 4\nLUT_3D_SIZE 2\n", {"lut.cube:2:", "a second size line"});
  refuse("0 0 0\n", {"lut.cube:1:", "a data row before LUT_1D_SIZE"});
  refuse("LUT_1D_SIZE 4\n0 0 0\nTITLE \"late\"\n", {"lut.cube:3:", "TITLE: a keyword after the data rows"});
  refuse("LUT_SIZE 4\n", {"lut.cube:1:", "unknown keyword 'LUT_SIZE'"});
  refuse("# nothing\n", {"lut.cube:1:", "no LUT_1D_SIZE or LUT_3D_SIZE"});
  refuse("TITLE \"a\"\nTITLE \"b\"\n", {"lut.cube:2:", "TITLE: given twice"});
}

// ---- the stages against their closed forms ---------------------------------------

TEST(MpcdiColourProfile, GammaDecodeAndEncodeFollowTheClosedForm) {
  MpcdiColourProfile p;
  p.decode.gamma = 2.4;
  p.encode = {MpcdiColourProfile::Encode::Type::gamma, 1.8, std::nullopt};
  for (const double code : {0.0, 1.0, 17.0, 128.0, 200.0, 255.0}) {
    const double e = code / 255.0;  // §2.5.1.2.4: Linear = (Encoded / Scale)^gamma
    EXPECT_NEAR(p.decoded({e, e, e})[1], std::pow(e, 2.4), 1e-15) << code;
    EXPECT_NEAR(p.encoded({e, e, e})[2], std::pow(e, 1.0 / 1.8), 1e-15) << code;  // Encoded = Scale · Linear^(1/γ)
    // processPixel: decode, α · L · (1 − β) + β, encode.
    const double alpha = 0.6, beta = 0.03;
    EXPECT_NEAR(p.process({e, e, e}, alpha, beta)[0], std::pow(alpha * std::pow(e, 2.4) * (1 - beta) + beta, 1 / 1.8),
                1e-15)
        << code;
  }
  // Encode "none": the linear value is sent as is (a linear display, §2.5.1.3).
  MpcdiColourProfile linear;
  linear.decode.gamma = 2.2;
  EXPECT_NEAR(linear.process({0.5, 0.5, 0.5}, 1.0, 0.0)[0], std::pow(0.5, 2.2), 1e-15);
}

TEST(MpcdiColourProfile, AnIdentity1dLutGivesTheIdentity) {
  MpcdiColourProfile p;
  p.decode.type = MpcdiColourProfile::Decode::Type::lut1d;
  p.decode.lut = parse_cube_lut(cube_1d(17, [](double x) { return Rgb{x, x, x}; }), "id.cube");
  p.correct.type = MpcdiColourProfile::Correct::Type::lut1d_primary;
  p.correct.lut = p.decode.lut;
  p.encode = {MpcdiColourProfile::Encode::Type::lut1d, 1.0, p.decode.lut};
  for (int k = 0; k <= 1000; ++k) {
    const double x = k / 1000.0, y = 1.0 - x, z = 0.5 * x;
    const Rgb out = p.process({x, y, z}, 1.0, 0.0);
    // Entries i / 16 in binary32 (exact for these), interpolated in double.
    EXPECT_NEAR(out[0], x, 1e-7);
    EXPECT_NEAR(out[1], y, 1e-7);
    EXPECT_NEAR(out[2], z, 1e-7);
  }
}

TEST(MpcdiColourProfile, APrimariesMatrixIsAppliedAsTheStandardsPseudoCodeWritesIt) {
  MpcdiColourProfile p;
  p.correct.type = MpcdiColourProfile::Correct::Type::lut1d_primary;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) p.correct.primaries[i][j] = kMatrix[i][j];
  // By hand, (0.2, 0.5, 0.9):
  //   Rout = 0.2·0.80 + 0.5·0.15 + 0.9·0.03 = 0.16 + 0.075 + 0.027 = 0.262
  //   Gout = 0.2·0.05 + 0.5·0.90 + 0.9·0.02 = 0.01 + 0.45 + 0.018 = 0.478
  //   Bout = 0.2·0.02 + 0.5·0.08 + 0.9·0.85 = 0.004 + 0.04 + 0.765 = 0.809
  const Rgb out = p.corrected({0.2, 0.5, 0.9});
  EXPECT_NEAR(out[0], 0.262, 1e-15);
  EXPECT_NEAR(out[1], 0.478, 1e-15);
  EXPECT_NEAR(out[2], 0.809, 1e-15);
}

TEST(MpcdiColourProfile, A3dLutOfAMatrixIsExactAtLatticePointsAndWithinTheTrilinearBoundBetween) {
  // Trilinear interpolation reproduces an affine function exactly: a matrix is
  // exact everywhere up to the binary32 rounding of the lattice values
  // (≤ 2^-24 · 1, ≈ 6e-8). A non-linear function f = matrix · v² has the
  // bound (h² / 8) · Σ_axes max|∂²f/∂x²| = (h² / 8) · 2 · max row sum (h = 1 / (n − 1)).
  constexpr int n = 9;
  const CubeLut linear = parse_cube_lut(cube_3d(n, times_matrix), "m.cube");
  const auto squared = [](const Rgb& v) { return times_matrix({v[0] * v[0], v[1] * v[1], v[2] * v[2]}); };
  const CubeLut curved = parse_cube_lut(cube_3d(n, squared), "m2.cube");
  for (int b = 0; b < n; ++b)
    for (int g = 0; g < n; ++g)
      for (int r = 0; r < n; ++r) {
        const Rgb v = {r / (n - 1.0), g / (n - 1.0), b / (n - 1.0)};
        const Rgb want = squared(v), got = curved.apply(v);
        for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 6e-8);
      }
  const double h = 1.0 / (n - 1), bound = h * h / 8.0 * 2.0 * 0.98;  // largest row sum 0.98
  double worst = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Rgb v = {std::fmod(0.137 * k, 1.0), std::fmod(0.291 * k + 0.05, 1.0), std::fmod(0.071 * k + 0.3, 1.0)};
    const Rgb exact = times_matrix(v), got = linear.apply(v);
    for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(got[c], exact[c], 2e-7);
    const Rgb want2 = squared(v), got2 = curved.apply(v);
    for (std::size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got2[c] - want2[c]));
  }
  EXPECT_LE(worst, bound + 1e-7);
  EXPECT_GT(worst, 0.25 * bound);  // the bound is a real one: the error reaches a good part of it
}

// ---- <color> in archives ------------------------------------------------------------

/// mpcdi.xml of one region "p1" (64 × 48) of `profile` with `color` inside the
/// region and `fileset` inside its fileset; colour level `level`.
std::string descriptor(const std::string& profile, const std::string& color, const std::string& fileset,
                       const std::string& level = "5") {
  const bool frustum = profile == "3d" || profile == "sl";
  const std::string region_inner =
      (frustum ? std::string("<frustum><yaw>0</yaw><pitch>0</pitch><roll>0</roll><rightAngle>30</rightAngle>"
                             "<leftAngle>-30</leftAngle><upAngle>20</upAngle><downAngle>-20</downAngle></frustum>\n")
               : std::string()) +
      (profile == "sl" ? std::string("<coordinateFrame><posx>0</posx><posy>0</posy><posz>0</posz><yawx>0</yawx>"
                                     "<yawy>-1</yawy><yawz>0</yawz><pitchx>-1</pitchx><pitchy>0</pitchy>"
                                     "<pitchz>0</pitchz><rollx>0</rollx><rolly>0</rolly><rollz>1</rollz>"
                                     "</coordinateFrame>\n")
                       : std::string());
  const std::string warp = profile == "2d"   ? "<geometryWarpFile><path>w.pfm</path></geometryWarpFile>\n"
                           : profile == "a3" ? "<geometryWarpFile><path>p.pfm</path><geometricUnit>m</geometricUnit>"
                                               "<originOf3DData>idealEyePoint</originOf3DData></geometryWarpFile>\n"
                                             : "";
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<MPCDI profile=\"{}\" geometry=\"2\" color=\"{}\" "
      "version=\"2.0\">\n<display>\n<buffer id=\"b\" xResolution=\"64\" yResolution=\"48\">\n"
      "<region id=\"p1\" x=\"0\" y=\"0\" xsize=\"1\" ysize=\"1\" xResolution=\"64\" yResolution=\"48\">\n"
      "{}{}</region>\n</buffer>\n</display>\n<files>\n<fileset region=\"p1\">\n{}{}</fileset>\n</files>\n</MPCDI>\n",
      profile, level, region_inner, color, warp, fileset);
}

/// The members every profile's region needs besides mpcdi.xml: a 2D warp
/// (identity, 2d) and 3D screen points (a3: a plane 5 m ahead of the eye).
Members geometry_members() {
  return {{"w.pfm",
           make_pfm(
               4, 3, 3, [](int x, int y, int c) { return c == 0   ? x / 3.0f
                                                         : c == 1 ? y / 2.0f
                                                                  : 0.0f; }, true, true)},
          {"p.pfm", make_pfm(
                        4, 3, 3,
                        [](int x, int y, int c) {
                          return c == 0 ? 3.0f - 2.0f * x : c == 1 ? 2.0f - 2.0f * y : 5.0f;  // X left, Y up, Z ahead
                        },
                        true, true)}};
}

std::filesystem::path colour_archive(const ScratchDir& dir, const std::string& name, const std::string& xml,
                                     Members luts = {}) {
  Members members = geometry_members();
  members.emplace_back("mpcdi.xml", xml);
  for (auto& m : luts) members.push_back(std::move(m));
  return testing::make_zip(dir, name, members);
}

const char* const kGammaColour =
    "<color><decode type=\"gamma\" gamma=\"2.4\"/><correct type=\"none\"/>"
    "<encode type=\"gamma\" gamma=\"2.2\"/></color>\n";

TEST(MpcdiColour, ARegionOfEveryProfileReadsItsColourProfile) {
  ScratchDir dir("mpcdi_colour_profiles");
  for (const std::string profile : {"2d", "3d", "a3", "sl"}) {
    const MpcdiFile file =
        load_mpcdi(colour_archive(dir, fmt::format("{}.mpcdi", profile), descriptor(profile, kGammaColour, "")));
    const MpcdiRegion& region = *file.find_region("p1");
    ASSERT_TRUE(region.colour) << profile;
    EXPECT_EQ(region.colour->decode.type, MpcdiColourProfile::Decode::Type::gamma);
    EXPECT_EQ(region.colour->decode.gamma, 2.4);
    EXPECT_EQ(region.colour->correct.type, MpcdiColourProfile::Correct::Type::none);
    EXPECT_EQ(region.colour->encode.type, MpcdiColourProfile::Encode::Type::gamma);
    EXPECT_EQ(region.colour->encode.gamma, 2.2);
    EXPECT_EQ(file.colour_level, 5);
    // Through a viewport config: the output carries it.
    json output = {{"name", "o"},
                   {"size", {64, 48}},
                   {"warp", {{"file", fmt::format("{}.mpcdi", profile)}, {"format", "mpcdi"}, {"region", "p1"}}}};
    if (profile == "2d")
      output["projection"] = {
          {"type", "planar"}, {"left_deg", -30}, {"right_deg", 30}, {"down_deg", -20}, {"up_deg", 20}};
    if (profile == "a3") output["warp"]["eye"] = {0, 0, 0};
    const ViewportConfig config = parse_viewport_config(
        json{{"zenith_viewports", 1}, {"name", "t"}, {"outputs", json::array({output})}}, "t.json", dir.path());
    ASSERT_TRUE(config.outputs[0].colour) << profile;
    EXPECT_EQ(describe(*config.outputs[0].colour), "decode gamma 2.4, correct none, encode gamma 2.2");
  }
  // No <color>: no profile (zenith's own output stage, as before).
  const std::string bare = descriptor("2d", "", "");
  EXPECT_FALSE(load_mpcdi(colour_archive(dir, "bare.mpcdi", bare)).find_region("p1")->colour);
}

TEST(MpcdiColour, LutsOfTheFilesetAreReadForTheTypesThatNeedThem) {
  ScratchDir dir("mpcdi_colour_luts");
  const std::string color =
      "<color><decode type=\"lut1d\"/><correct type=\"lut1d-primary\"><primaries>"
      "<redPrimary><red>0.8</red><green>0.15</green><blue>0.03</blue></redPrimary>"
      "<greenPrimary><red>0.05</red><green>0.9</green><blue>0.02</blue></greenPrimary>"
      "<bluePrimary><red>0.02</red><green>0.08</green><blue>0.85</blue></bluePrimary>"
      "</primaries></correct><encode type=\"lut1d\"/></color>\n";
  const std::string fileset =
      "<decodeLUT><path>luts/decode.cube</path><interpolation>linear</interpolation></decodeLUT>\n"
      "<correctLUT><path>luts/correct.cube</path><interpolation>smooth</interpolation></correctLUT>\n"
      "<encodeLUT><path>luts/encode.cube</path><interpolation>unknown</interpolation></encodeLUT>\n";
  const auto power = [](double g) {
    return [g](double x) { return Rgb{std::pow(x, g), std::pow(x, g), std::pow(x, g)}; };
  };
  const MpcdiFile file = load_mpcdi(colour_archive(dir, "luts.mpcdi", descriptor("3d", color, fileset, "4"),
                                                   {{"luts/decode.cube", cube_1d(1024, power(2.2))},
                                                    {"luts/correct.cube", cube_1d(4, power(1.0))},
                                                    {"luts/encode.cube", cube_1d(4096, power(1 / 2.2))}}));
  const MpcdiColourProfile& c = *file.find_region("p1")->colour;
  ASSERT_TRUE(c.decode.lut && c.correct.lut && c.encode.lut);
  EXPECT_EQ(c.decode.lut->size, 1024);
  EXPECT_EQ(c.encode.lut->size, 4096);
  EXPECT_EQ(c.correct.primaries[0][1], 0.15);
  EXPECT_EQ(c.correct.primaries[2][1], 0.08);
  // The whole chain against the closed form of its parts: (M · x^2.2)^(1/2.2),
  // within the 1D LUTs' interpolation error (h² / 8 · max|f''|, largest near 0 for the encode).
  const Rgb x = {0.3, 0.6, 0.9};
  const Rgb l = times_matrix({std::pow(0.3, 2.2), std::pow(0.6, 2.2), std::pow(0.9, 2.2)});
  const Rgb got = c.process(x, 1.0, 0.0);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(got[k], std::pow(l[k], 1 / 2.2), 2e-4) << k;

  // Level 5: a 3D correct and encode.
  const std::string color5 =
      "<color><decode type=\"gamma\" gamma=\"2.2\"/><correct type=\"lut3d\"/>"
      "<encode type=\"lut3d\"/></color>\n";
  const std::string fileset5 =
      "<correctLUT><path>c3.cube</path></correctLUT><encodeLUT><path>e3.cube</path></encodeLUT>\n";
  const MpcdiFile five = load_mpcdi(colour_archive(
      dir, "five.mpcdi", descriptor("sl", color5, fileset5, "5"),
      {{"c3.cube", cube_3d(17, times_matrix)}, {"e3.cube", cube_3d(2, [](const Rgb& v) { return v; })}}));
  const MpcdiColourProfile& c5 = *five.find_region("p1")->colour;
  ASSERT_TRUE(c5.correct.lut && c5.correct.lut->is_3d() && c5.encode.lut && c5.encode.lut->is_3d());
  const Rgb m = times_matrix({std::pow(0.3, 2.2), std::pow(0.6, 2.2), std::pow(0.9, 2.2)});
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(c5.process(x, 1.0, 0.0)[k], m[k], 2e-7) << k;
}

TEST(MpcdiColour, EveryRefusalNamesTheArchiveTheLineAndTheElement) {
  ScratchDir dir("mpcdi_colour_refusals");
  int n = 0;
  const auto refuse = [&](const std::string& xml, const Members& luts, const std::vector<std::string>& parts) {
    const std::string name = fmt::format("r{}.mpcdi", n++);
    const auto path = colour_archive(dir, name, xml, luts);
    std::vector<std::string> all = {name};
    all.insert(all.end(), parts.begin(), parts.end());
    expect_error([&] { load_mpcdi(path); }, all);
  };
  const auto id1d = cube_1d(4, [](double x) { return Rgb{x, x, x}; });
  const auto id3d = cube_3d(2, [](const Rgb& v) { return v; });
  // The <color> element's own fields (line 6: the region's first line is 5, <color> the next for 2d).
  refuse(descriptor("2d", "<color><encode type=\"gamma\" gamma=\"2.2\"/></color>\n", ""), {},
         {"mpcdi.xml:6:", "region 'p1'", "<color> has no <decode>"});
  refuse(descriptor("2d", "<color><decode type=\"srgb\"/><encode type=\"none\"/></color>\n", ""), {},
         {"mpcdi.xml:6:", "<decode> type 'srgb': must be one of gamma, lut1d, none"});
  refuse(descriptor("2d", "<color><decode type=\"gamma\"/><encode type=\"none\"/></color>\n", ""), {},
         {"mpcdi.xml:6:", "<decode> type 'gamma' has no attribute 'gamma'"});
  refuse(descriptor("2d", "<color><decode type=\"gamma\" gamma=\"0\"/><encode type=\"none\"/></color>\n", ""), {},
         {"mpcdi.xml:6:", "<decode> attribute 'gamma' = 0: must be in [0.1, 10]"});
  refuse(descriptor("2d", "<color><decode type=\"gamma\" gamma=\"2.2\"/></color>\n", ""), {},
         {"mpcdi.xml:6:", "<color> has no <encode>"});
  refuse(descriptor("2d",
                    "<color><decode type=\"gamma\" gamma=\"2.2\"/><correct type=\"lut1d-primary\"><primaries>"
                    "<redPrimary><red>1</red><green>x</green><blue>0</blue></redPrimary></primaries></correct>"
                    "<encode type=\"none\"/></color>\n",
                    ""),
         {}, {"mpcdi.xml:6:", "<redPrimary> <green> = 'x' is not a finite number"});
  refuse(descriptor("2d",
                    "<color><decode type=\"gamma\" gamma=\"2.2\"/><correct type=\"lut1d-primary\"><primaries>"
                    "<redPrimary><red>1</red><green>0</green><blue>0</blue></redPrimary></primaries></correct>"
                    "<encode type=\"none\"/></color>\n",
                    ""),
         {}, {"mpcdi.xml:6:", "<primaries> has no <greenPrimary>"});
  // LUTs: missing, of the wrong kind, above the colour level, broken.
  const std::string lut_decode = "<color><decode type=\"lut1d\"/><encode type=\"gamma\" gamma=\"2.2\"/></color>\n";
  refuse(descriptor("3d", lut_decode, ""), {}, {"region 'p1'", "<decode> type 'lut1d' needs a <decodeLUT>"});
  refuse(descriptor("3d", lut_decode, "<decodeLUT><path>d.cube</path></decodeLUT>\n"), {{"d.cube", id3d}},
         {"<decodeLUT> 'd.cube' is a 3D LUT; <decode> type 'lut1d' needs a 1D one"});
  refuse(descriptor("3d", lut_decode, "<decodeLUT><path>d.cube</path></decodeLUT>\n", "2"), {{"d.cube", id1d}},
         {"<decode> type 'lut1d' needs colour level 3 or higher", "color=\"2\""});
  refuse(descriptor("a3",
                    "<color><decode type=\"gamma\" gamma=\"2.2\"/><correct type=\"lut3d\"/><encode type=\"none\"/>"
                    "</color>\n",
                    "<correctLUT><path>c.cube</path></correctLUT>\n", "4"),
         {{"c.cube", id3d}}, {"<correct> type 'lut3d' needs colour level 5 or higher", "color=\"4\""});
  refuse(descriptor("sl", lut_decode, "<decodeLUT><path>d.cube</path></decodeLUT>\n"), {},
         {"region 'p1'", "decodeLUT 'd.cube' is not in the archive"});
  refuse(descriptor("2d", lut_decode, "<decodeLUT><path>d.cube</path></decodeLUT>\n"),
         {{"d.cube", "LUT_1D_SIZE 4\n0 0 0\n1 1 1\n"}}, {":d.cube:3:", "2 rows of data; LUT_1D_SIZE 4 needs 4"});
  refuse(descriptor("2d", lut_decode,
                    "<decodeLUT><path>d.cube</path><interpolation>keystone</interpolation></decodeLUT>\n"),
         {{"d.cube", id1d}}, {"<interpolation> 'keystone': must be linear, smooth or unknown"});
  refuse(descriptor("2d", kGammaColour, "", "6"), {}, {"mpcdi.xml:2:", "attribute 'color'", "[1, 5]"});
}

TEST(MpcdiColour, AWindowEncodingBesideARegionsColourIsRefused) {
  ScratchDir dir("mpcdi_colour_window");
  colour_archive(dir, "g.mpcdi", descriptor("3d", kGammaColour, ""));
  const json output = {{"name", "o"},
                       {"size", {64, 48}},
                       {"warp", {{"file", "g.mpcdi"}, {"format", "mpcdi"}, {"region", "p1"}}},
                       {"window", {{"encoding", {{"gamma", 2.4}}}}}};
  testing::expect_config_error(
      [&] {
        parse_viewport_config(json{{"zenith_viewports", 1}, {"name", "t"}, {"outputs", json::array({output})}},
                              "t.json", dir.path());
      },
      "t.json", "/outputs/0/window", "whose <color> encodes for the projector");
}

}  // namespace
}  // namespace zenith::warp
