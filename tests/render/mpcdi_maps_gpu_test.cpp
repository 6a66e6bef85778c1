// An MPCDI region's alpha and beta maps in the display pass: the
// output's α and β from an archive whose maps are smaller than the output
// (warp/mpcdi_blend.h), as one rg32f texture (α, β) on the GPU
// (render/display/display_encoder.h) against the CPU path that writes files
// (warp::apply_blend, render/display/colour_signal.h) and against
// α·L·(1 − β) + β worked out here, with and without a colour profile.
//
// Bounds. α and β reach both paths as the same floats (the mask the CPU
// samples once); the GPU then computes P' = α·L·(1 − β) + β and its encoding
// in float, the CPU in double: a few ulp before the rounding, so ±1 code in 8
// and 16 bits, as the plain display pass (display_encoder_test.cpp). The
// independent values (double, tent weights) differ from the mask's floats by
// at most 1e-7, well inside a 16-bit code at the encoding's steepest slope
// above the β ≥ 0.04 this archive has (12.92 · 1e-7 = 1.3e-6 < 1 / 65535).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "image/display_encoding.h"
#include "image/tone_mapping.h"
#include "render/display/colour_profile_textures.h"
#include "render/display/colour_signal.h"
#include "render/display/display_encoder.h"
#include "tests/render/display_test_support.h"
#include "tests/render/render_test_support.h"
#include "tests/warp/mpcdi_test_support.h"
#include "warp/blending.h"
#include "warp/colour_profile.h"
#include "warp/viewport_config.h"

namespace zenith::render::display {
namespace {

using testing::context;
using Profile = warp::MpcdiColourProfile;

constexpr int kWidth = 64, kHeight = 48;
constexpr int kAlphaWidth = 9, kAlphaHeight = 7, kBetaWidth = 5, kBetaHeight = 4;
constexpr double kGammaEmbedded = 2.2;

std::uint16_t alpha_stored(int i, int j) { return static_cast<std::uint16_t>(65535 - 6000 * i - 1500 * j); }
unsigned char beta_stored(int i, int j) { return static_cast<unsigned char>(10 + 7 * i + 11 * j); }  // 0.04 to 0.28
double alpha_linear(int i, int j) { return std::pow(alpha_stored(i, j) / 65535.0, kGammaEmbedded); }
double beta_linear(int i, int j) { return beta_stored(i, j) / 255.0; }

/// Exposed radiance from 1e-4 to 40 along the frame, the channels offset.
std::vector<float> test_radiance() { return testing::geometric_radiance(kWidth, kHeight, 1e-4, 4e5); }

/// The archive's output: "blend": {"type": "mpcdi"}.
warp::ViewportConfig maps_config(const warp::testing::ScratchDir& dir) {
  const std::vector<std::uint16_t> alpha = warp::testing::map_samples(kAlphaWidth, kAlphaHeight, alpha_stored);
  const std::vector<unsigned char> beta = warp::testing::map_samples(kBetaWidth, kBetaHeight, beta_stored);
  warp::testing::make_zip(dir, "maps.mpcdi",
                          {{"mpcdi.xml", warp::testing::descriptor_with_maps(
                                             {{"p", kWidth, kHeight,
                                               warp::testing::map_element("alphaMap", "a.png", 1, 16, kGammaEmbedded) +
                                                   warp::testing::map_element("betaMap", "b.png", 1, 8)}})},
                           {"p.pfm", warp::testing::identity_warp()},
                           {"a.png", warp::testing::make_grey_png(kAlphaWidth, kAlphaHeight, alpha)},
                           {"b.png", warp::testing::make_grey_png(kBetaWidth, kBetaHeight, beta)}});
  const nlohmann::json output = {{"name", "p"},
                                 {"size", {kWidth, kHeight}},
                                 {"projection", {{"type", "planar"}, {"fov_deg", 70}}},
                                 {"warp", {{"file", "maps.mpcdi"}, {"format", "mpcdi"}, {"region", "p"}}},
                                 {"blend", {{"type", "mpcdi"}}}};
  return warp::parse_viewport_config(
      {{"zenith_viewports", 1}, {"name", "maps"}, {"outputs", nlohmann::json::array({output})}}, "maps.json",
      dir.path());
}

/// The GPU's codes of the test frame through `stage`.
std::vector<int> gpu_codes(const OutputStage& stage, gl::TextureFormat format) {
  return testing::display_codes(test_radiance(), kWidth, kHeight, stage, format);
}

/// The tone mapped test frame, display-linear RGB.
std::vector<float> tone_mapped() {
  const std::vector<float> rgba = test_radiance();
  std::vector<float> rgb;
  for (std::size_t i = 0; i < rgba.size(); ++i)
    if (i % 4 != 3) rgb.push_back(image::tone_map(rgba[i], image::ToneMapping::exponential));
  return rgb;
}

std::vector<int> to_codes(const std::vector<double>& values, int bits) {
  const double top = bits == 8 ? 255.0 : 65535.0;
  std::vector<int> codes;
  for (const double v : values) codes.push_back(static_cast<int>(std::lround(v * top)));
  return codes;
}

int worst(const std::vector<int>& a, const std::vector<int>& b) { return testing::worst_code_difference(a, b); }

TEST(MpcdiMapsGpu, AlphaAndBetaMapsGiveTheSameCodesOnTheGpuTheCpuAndByHand) {
  context();
  warp::testing::ScratchDir dir("mpcdi_maps_gpu");
  const warp::ViewportConfig config = maps_config(dir);
  const warp::BlendMask mask = warp::output_blend_mask(config, 0);
  ASSERT_FALSE(mask.beta.empty());
  const gl::Texture mask_texture = blend_mask_texture(mask);
  EXPECT_EQ(mask_texture.format(), gl::TextureFormat::rg32f);  // α and β, uploaded once
  OutputStage stage;
  stage.blended = true;
  stage.blend_mask = &mask_texture;
  stage.black_level = 0.5;  // not used: the mask's β

  // By hand: V = sRGB(α · L · (1 − β) + β), α and β the maps' tent sums.
  const std::vector<float> linear = tone_mapped();
  std::vector<double> by_hand;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const double a = warp::testing::tent_sum(alpha_linear, kAlphaWidth, kAlphaHeight, kWidth, kHeight, x, y);
      const double b = warp::testing::tent_sum(beta_linear, kBetaWidth, kBetaHeight, kWidth, kHeight, x, y);
      for (int c = 0; c < 3; ++c) {
        const double l = linear[(static_cast<std::size_t>(y) * kWidth + x) * 3 + c];
        by_hand.push_back(image::display_encode(a * l * (1.0 - b) + b, {}));
      }
    }
  // The CPU path: apply_blend with the mask (its β), then the encoding.
  std::vector<float> cpu = linear;
  warp::apply_blend(cpu, 0, kHeight, mask, 0.5);
  std::vector<double> cpu_signal;
  for (const float v : cpu) cpu_signal.push_back(image::display_encode(v, {}));
  for (const int bits : {8, 16}) {
    SCOPED_TRACE(bits);
    const std::vector<int> gpu = gpu_codes(stage, bits == 8 ? gl::TextureFormat::rgba8 : gl::TextureFormat::rgba16);
    EXPECT_LE(worst(gpu, to_codes(cpu_signal, bits)), 1);
    EXPECT_LE(worst(gpu, to_codes(by_hand, bits)), 1);
    EXPECT_LE(worst(to_codes(cpu_signal, bits), to_codes(by_hand, bits)), 1);
  }
  // The maps matter: without them (α = 1, β = 0) most codes differ by far more.
  OutputStage plain;
  EXPECT_GT(worst(gpu_codes(plain, gl::TextureFormat::rgba8), gpu_codes(stage, gl::TextureFormat::rgba8)), 40);
}

TEST(MpcdiMapsGpu, WithAColourProfileTheMapsEnterProcessPixelAlikeOnBothPaths) {
  context();
  warp::testing::ScratchDir dir("mpcdi_maps_gpu_colour");
  const warp::ViewportConfig config = maps_config(dir);
  const warp::BlendMask mask = warp::output_blend_mask(config, 0);
  const gl::Texture mask_texture = blend_mask_texture(mask);
  Profile p;
  p.decode.gamma = 2.2;
  p.correct.type = Profile::Correct::Type::lut1d_primary;
  p.correct.primaries = {{{0.80, 0.15, 0.03}, {0.05, 0.90, 0.02}, {0.02, 0.08, 0.85}}};
  warp::CubeLut encode{warp::CubeLut::Kind::lut_1d, "", 4096, {}};
  for (int i = 0; i < 4096; ++i)
    for (int c = 0; c < 3; ++c) encode.rgb.push_back(static_cast<float>(std::pow(i / 4095.0, 1 / 2.4)));
  p.encode = {Profile::Encode::Type::lut1d, 1.0, encode};
  const ColourProfileTextures textures(p);
  OutputStage stage;
  stage.blended = true;
  stage.blend_mask = &mask_texture;
  stage.colour = &textures;
  std::vector<float> cpu = tone_mapped();
  apply_colour_profile(cpu, 0, kHeight, kWidth, p, &mask, 0.0);
  const std::vector<double> cpu_signal(cpu.begin(), cpu.end());
  // processPixel by hand at one pixel: β enters after the correction, α·L·(1 − β) + β.
  const int x = 40, y = 30;
  const double a = warp::testing::tent_sum(alpha_linear, kAlphaWidth, kAlphaHeight, kWidth, kHeight, x, y);
  const double b = warp::testing::tent_sum(beta_linear, kBetaWidth, kBetaHeight, kWidth, kHeight, x, y);
  const std::vector<float> linear = tone_mapped();
  const std::size_t k = (static_cast<std::size_t>(y) * kWidth + x) * 3;
  std::array<double, 3> s{};
  for (std::size_t c = 0; c < 3; ++c) s[c] = image::display_encode(linear[k + c], {});
  EXPECT_NEAR(cpu[k + 1], p.process(s, a, b)[1], 1e-6);
  for (const int bits : {8, 16}) {
    SCOPED_TRACE(bits);
    EXPECT_LE(worst(gpu_codes(stage, bits == 8 ? gl::TextureFormat::rgba8 : gl::TextureFormat::rgba16),
                    to_codes(cpu_signal, bits)),
              1);
  }
}

}  // namespace
}  // namespace zenith::render::display
