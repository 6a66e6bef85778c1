// An MPCDI region's colour profile in the display pass: the GPU's
// codes (render/display/display_encoder.h, display_transform.glsl) against the
// CPU path that writes files (render/display/colour_signal.h), and a region of
// each profile loaded from an archive whose frame differs from the identity
// one as the closed form of its gammas says.
//
// Bounds. Without a 3D LUT the GPU computes the same operations in float as
// the CPU in double (pow, a matrix, 1D LUT lerps between exact entries): a few
// ulp before the rounding, so ±1 code in 8 and 16 bits, as the plain display
// pass. A 3D LUT is filtered by the texture unit, whose weights are fixed
// point (8 fractional bits on NVIDIA): within 2^−9 · Δ of the exact trilinear
// value, Δ the largest step between neighbouring lattice values (0.06 for the
// 17³ matrix LUT: 1.2e-4 a channel, at most 3.5e-4 over three axes), which
// the encode x^(1/2.4) amplifies by at most (1/2.4) · β^(−0.58) = 2.4 at the
// black level β = 0.05 the test keeps: 8.5e-4 = 0.22 of an 8-bit code, so ±1
// in 8 bits; 16-bit codes are then good to about 60 codes (not tested).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "image/display_encoding.h"
#include "image/srgb_quantizer.h"
#include "image/tone_mapping.h"
#include "render/display/colour_profile_textures.h"
#include "render/display/colour_signal.h"
#include "render/display/display_encoder.h"
#include "tests/render/display_test_support.h"
#include "tests/render/render_test_support.h"
#include "tests/warp/mpcdi_test_support.h"
#include "warp/blending.h"
#include "warp/colour_profile.h"
#include "warp/cube_lut.h"
#include "warp/viewport_config.h"

namespace zenith::render::display {
namespace {

using testing::context;
using Rgb = std::array<double, 3>;
using Profile = warp::MpcdiColourProfile;

constexpr int kWidth = 64, kHeight = 48;

/// Exposed radiance from 1e-4 to 40 along the frame, the channels offset.
std::vector<float> test_radiance() { return testing::geometric_radiance(kWidth, kHeight, 1e-4, 4e5); }

warp::BlendMask test_mask() {
  warp::BlendMask m{kWidth, kHeight, std::vector<float>(static_cast<std::size_t>(kWidth) * kHeight)};
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) m.alpha[static_cast<std::size_t>(y) * kWidth + x] = x / float(kWidth - 1);
  return m;
}

warp::CubeLut lut_1d(int n, const std::function<double(double)>& f) {
  warp::CubeLut lut{warp::CubeLut::Kind::lut_1d, "", n, {}};
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) lut.rgb.push_back(static_cast<float>(f(i / (n - 1.0))));
  return lut;
}

warp::CubeLut lut_3d(int n, const std::function<Rgb(const Rgb&)>& f) {
  warp::CubeLut lut{warp::CubeLut::Kind::lut_3d, "", n, {}};
  for (int b = 0; b < n; ++b)
    for (int g = 0; g < n; ++g)
      for (int r = 0; r < n; ++r) {
        const Rgb v = f({r / (n - 1.0), g / (n - 1.0), b / (n - 1.0)});
        for (const double x : v) lut.rgb.push_back(static_cast<float>(x));
      }
  return lut;
}

constexpr std::array<Rgb, 3> kMatrix = {{{0.80, 0.15, 0.03}, {0.05, 0.90, 0.02}, {0.02, 0.08, 0.85}}};
Rgb times_matrix(const Rgb& v) {
  Rgb out{};
  for (std::size_t i = 0; i < 3; ++i) out[i] = kMatrix[i][0] * v[0] + kMatrix[i][1] * v[1] + kMatrix[i][2] * v[2];
  return out;
}

/// The GPU's codes of the test frame through `stage`.
std::vector<int> gpu_codes(const OutputStage& stage, gl::TextureFormat format) {
  return testing::display_codes(test_radiance(), kWidth, kHeight, stage, format);
}

/// The CPU path's codes: tone mapping, then apply_colour_profile with the mask and β.
std::vector<int> cpu_codes(const Profile& profile, const warp::BlendMask* mask, double black_level, int bits) {
  const std::vector<float> rgba = test_radiance();
  std::vector<float> rgb;
  for (std::size_t i = 0; i < rgba.size(); ++i)
    if (i % 4 != 3) rgb.push_back(image::tone_map(rgba[i], image::ToneMapping::exponential));
  apply_colour_profile(rgb, 0, kHeight, kWidth, profile, mask, black_level);
  const double top = bits == 8 ? 255.0 : 65535.0;
  std::vector<int> codes;
  for (const float v : rgb) codes.push_back(static_cast<int>(std::lround(v * top)));
  return codes;
}

int worst(const std::vector<int>& a, const std::vector<int>& b) { return testing::worst_code_difference(a, b); }

/// The worst code difference GPU − CPU for `profile` with the test mask and β = 0.05.
int worst_difference(const Profile& profile, gl::TextureFormat format) {
  context();
  const warp::BlendMask mask = test_mask();
  const gl::Texture mask_texture = blend_mask_texture(mask);
  const ColourProfileTextures textures(profile);
  OutputStage stage;
  stage.blended = true;
  stage.blend_mask = &mask_texture;
  stage.black_level = 0.05;
  stage.colour = &textures;
  return worst(gpu_codes(stage, format), cpu_codes(profile, &mask, 0.05, format == gl::TextureFormat::rgba8 ? 8 : 16));
}

TEST(ColourProfileGpu, GammasPrimariesAnd1dLutsEqualTheCpuPathWithinOneCodeIn8And16Bits) {
  Profile gamma;
  gamma.decode.gamma = 2.2;
  gamma.correct.type = Profile::Correct::Type::lut1d_primary;
  gamma.correct.lut = lut_1d(33, [](double x) { return std::pow(x, 1.1); });
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) gamma.correct.primaries[i][j] = kMatrix[i][j];
  gamma.encode = {Profile::Encode::Type::gamma, 2.4, std::nullopt};
  EXPECT_LE(worst_difference(gamma, gl::TextureFormat::rgba8), 1);
  EXPECT_LE(worst_difference(gamma, gl::TextureFormat::rgba16), 1);

  // 1D LUTs past one texture row (1024 texels): 4096 and 65536 entries.
  Profile luts;
  luts.decode = {Profile::Decode::Type::lut1d, 1.0, lut_1d(4096, [](double x) { return std::pow(x, 2.2); })};
  luts.encode = {Profile::Encode::Type::lut1d, 1.0, lut_1d(65536, [](double x) { return std::pow(x, 1 / 2.4); })};
  EXPECT_LE(worst_difference(luts, gl::TextureFormat::rgba8), 1);
  EXPECT_LE(worst_difference(luts, gl::TextureFormat::rgba16), 1);
}

TEST(ColourProfileGpu, A3dLutEqualsTheCpuPathWithinTheTextureUnitsBound) {
  Profile p;
  p.decode.gamma = 2.2;
  p.correct = {Profile::Correct::Type::lut3d, lut_3d(17, times_matrix), {}};
  p.encode = {Profile::Encode::Type::gamma, 2.4, std::nullopt};
  EXPECT_LE(worst_difference(p, gl::TextureFormat::rgba8), 1);
  // A 3D encode LUT: x^(1/2.4) per channel on a 33³ lattice.
  Profile e;
  e.decode.gamma = 2.2;
  e.encode = {Profile::Encode::Type::lut3d, 1.0, lut_3d(33, [](const Rgb& v) {
                return Rgb{std::pow(v[0], 1 / 2.4), std::pow(v[1], 1 / 2.4), std::pow(v[2], 1 / 2.4)};
              })};
  EXPECT_LE(worst_difference(e, gl::TextureFormat::rgba8), 1);
}

TEST(ColourProfileGpu, MatchingGammasGiveZenithsOwnOutputStage) {
  // decode γ = encode γ = the display encoding's γ, correct none: processPixel
  // is then P' = α·P·(1 − β) + β encoded with γ, zenith's output stage exactly.
  context();
  const warp::BlendMask mask = test_mask();
  const gl::Texture mask_texture = blend_mask_texture(mask);
  OutputStage plain;
  plain.blended = true;
  plain.blend_mask = &mask_texture;
  plain.black_level = 0.05;
  plain.encoding = {image::DisplayEncoding::Transfer::gamma, 2.2};
  Profile p;
  p.decode.gamma = 2.2;
  p.encode = {Profile::Encode::Type::gamma, 2.2, std::nullopt};
  const ColourProfileTextures textures(p);
  OutputStage coloured = plain;
  coloured.colour = &textures;
  EXPECT_LE(worst(gpu_codes(coloured, gl::TextureFormat::rgba8), gpu_codes(plain, gl::TextureFormat::rgba8)), 1);
  EXPECT_LE(worst(gpu_codes(coloured, gl::TextureFormat::rgba16), gpu_codes(plain, gl::TextureFormat::rgba16)), 1);
}

TEST(ColourProfileGpu, ARegionOfEachProfileChangesItsFrameAsTheClosedFormSays) {
  // Each profile's region with <decode gamma 2.4> and <encode gamma 2.0>, no
  // blend: the frame's signal S = sRGB(P) becomes V = (S^2.4)^(1/2.0) = S^1.2.
  context();
  warp::testing::ScratchDir dir("colour_profile_gpu");
  const std::string color =
      "<color><decode type=\"gamma\" gamma=\"2.4\"/><correct type=\"none\"/><encode type=\"gamma\" gamma=\"2.0\"/>"
      "</color>\n";
  const std::string frustum =
      "<frustum><yaw>10</yaw><pitch>20</pitch><roll>0</roll><rightAngle>30</rightAngle><leftAngle>-30</leftAngle>"
      "<upAngle>20</upAngle><downAngle>-20</downAngle></frustum>\n";
  const std::string frame =
      "<coordinateFrame><posx>0</posx><posy>0</posy><posz>0</posz><yawx>0</yawx><yawy>-1</yawy><yawz>0</yawz>"
      "<pitchx>-1</pitchx><pitchy>0</pitchy><pitchz>0</pitchz><rollx>0</rollx><rolly>0</rolly><rollz>1</rollz>"
      "</coordinateFrame>\n";
  const auto plane = [](int x, int y, int c) { return c == 0 ? 3.0f - 2.0f * x : c == 1 ? 2.0f - 2.0f * y : 5.0f; };
  const auto grid = [](int x, int y, int c) { return c == 0 ? x / 3.0f : c == 1 ? y / 2.0f : 0.0f; };
  struct Case {
    std::string profile, region, fileset;
  };
  const std::vector<Case> cases = {{"2d", "", "<geometryWarpFile><path>w.pfm</path></geometryWarpFile>\n"},
                                   {"3d", frustum, ""},
                                   {"a3", "",
                                    "<geometryWarpFile><path>p.pfm</path><geometricUnit>m</geometricUnit>"
                                    "<originOf3DData>idealEyePoint</originOf3DData></geometryWarpFile>\n"},
                                   {"sl", frustum + frame, ""}};
  const std::vector<int> identity = [] {
    OutputStage plain;
    return gpu_codes(plain, gl::TextureFormat::rgba8);
  }();
  for (const Case& c : cases) {
    const std::string xml = fmt::format(
        "<?xml version=\"1.0\"?>\n<MPCDI profile=\"{}\" geometry=\"2\" color=\"2\" version=\"2.0\">\n<display>\n"
        "<buffer id=\"b\"><region id=\"p1\" x=\"0\" y=\"0\" xsize=\"1\" ysize=\"1\" xResolution=\"{}\" "
        "yResolution=\"{}\">\n{}{}</region></buffer>\n</display>\n<files><fileset region=\"p1\">\n{}</fileset>"
        "</files>\n</MPCDI>\n",
        c.profile, kWidth, kHeight, c.region, color, c.fileset);
    const std::string name = fmt::format("{}.mpcdi", c.profile);
    warp::testing::make_zip(dir, name,
                            {{"mpcdi.xml", xml},
                             {"w.pfm", warp::testing::make_pfm(4, 3, 3, grid, true, true)},
                             {"p.pfm", warp::testing::make_pfm(4, 3, 3, plane, true, true)}});
    nlohmann::json output = {
        {"name", "o"}, {"size", {kWidth, kHeight}}, {"warp", {{"file", name}, {"format", "mpcdi"}, {"region", "p1"}}}};
    if (c.profile == "2d") output["projection"] = {{"type", "fisheye"}};
    const warp::ViewportConfig config = warp::parse_viewport_config(
        nlohmann::json{{"zenith_viewports", 1}, {"name", "t"}, {"outputs", nlohmann::json::array({output})}}, "t.json",
        dir.path());
    ASSERT_TRUE(config.outputs[0].colour) << c.profile;
    const ColourProfileTextures textures(*config.outputs[0].colour);
    OutputStage stage;
    stage.colour = &textures;
    const std::vector<int> got = gpu_codes(stage, gl::TextureFormat::rgba8);
    const std::vector<float> rgba = test_radiance();
    int worst_closed_form = 0, changed = 0;
    for (std::size_t i = 0, k = 0; i < rgba.size(); ++i) {
      if (i % 4 == 3) continue;
      const double s = image::display_encode(image::tone_map(rgba[i], image::ToneMapping::exponential), {});
      const int want = static_cast<int>(std::lround(255.0 * std::pow(s, 1.2)));
      worst_closed_form = std::max(worst_closed_form, std::abs(got[k] - want));
      changed += got[k] != identity[k];
      ++k;
    }
    EXPECT_LE(worst_closed_form, 1) << c.profile;
    EXPECT_GT(changed, kWidth * kHeight) << c.profile;  // S^1.2 < S: most codes move
  }
}

TEST(ColourProfileCpu, TheSrgbPngWriterStoresTheCodesItIsGiven) {
  // The CPU path hands the PNG writer, which encodes sRGB, the centre of each
  // code (to_srgb_code_centres): every one of the 256 codes comes back.
  const image::SrgbQuantizer quantize;
  std::vector<float> v(256);
  for (int c = 0; c < 256; ++c) v[static_cast<std::size_t>(c)] = c / 255.0f;
  to_srgb_code_centres(v);
  for (int c = 0; c < 256; ++c) EXPECT_EQ(quantize(v[static_cast<std::size_t>(c)]), c) << c;
}

}  // namespace
}  // namespace zenith::render::display
