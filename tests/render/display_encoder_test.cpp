// The display pass on the GPU (render/display/display_encoder.h) against the
// CPU path it replaces for live frames: image::tone_map, the output stage
// (warp::blend_display_value) and image::display_code. Inputs span what a
// frame holds: 0, values below the exponential's series cut-over, the knee of
// the sRGB curve, bright values far past 1, and what must not reach a display
// (negative, NaN, +∞). The bound is ±1 code: the GPU's float arithmetic before
// the rounding (exp, pow: a few ulp) can move a value sitting within that of a
// rounding boundary to the neighbouring code, nothing more.
#include "render/display/display_encoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "image/display_encoding.h"
#include "image/tone_mapping.h"
#include "tests/render/render_test_support.h"
#include "warp/blending.h"

namespace zenith::render::display {
namespace {

using testing::context;

constexpr int kWidth = 64, kHeight = 48;

/// Exposed radiance covering the range: x grows geometrically along each row
/// (1e-6 … 40), the channels offset, with a few special values.
std::vector<float> test_radiance() {
  std::vector<float> rgba = testing::geometric_radiance(kWidth, kHeight, 1e-6, 4e7);
  rgba[0] = 0.0f;
  rgba[1] = -0.5f;
  rgba[2] = std::numeric_limits<float>::quiet_NaN();
  rgba[4] = std::numeric_limits<float>::infinity();
  rgba[5] = 1e-3f;  // the series' cut-over
  rgba[6] = 0.0031308f;
  return rgba;
}

/// A blend mask with a ramp and a zero column.
warp::BlendMask test_mask() {
  warp::BlendMask m{kWidth, kHeight, std::vector<float>(static_cast<std::size_t>(kWidth) * kHeight)};
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      m.alpha[static_cast<std::size_t>(y) * kWidth + x] = x == 0 ? 0.0f : x / float(kWidth - 1);
  return m;
}

/// α = 1 everywhere.
warp::BlendMask ones() {
  return {kWidth, kHeight, std::vector<float>(static_cast<std::size_t>(kWidth) * kHeight, 1.0f)};
}

/// A stage with the output stage on: `mask` (a texture of test_mask()) and black level β.
OutputStage blended(const gl::Texture& mask, double black_level) {
  OutputStage stage;
  stage.blended = true;
  stage.blend_mask = &mask;
  stage.black_level = black_level;
  return stage;
}

/// The CPU path's display-linear value of one channel.
float cpu_display_linear(float x, const OutputStage& stage, float alpha, int channel) {
  float p = image::tone_map(x, stage.tone);
  if (stage.fade.level > 0.0)
    p = static_cast<float>(p * (1.0 - stage.fade.level) +
                           stage.fade.colour[static_cast<std::size_t>(channel)] * stage.fade.level);
  if (stage.blended) p = static_cast<float>(warp::blend_display_value(p, alpha, stage.black_level));
  return p;
}

/// The largest difference in codes between the GPU's display texture and the CPU path.
int worst_code_difference(const OutputStage& stage, gl::TextureFormat format, const warp::BlendMask& mask) {
  context();
  const std::vector<float> input = test_radiance();
  const gl::Texture radiance = gl::Texture::create_2d(gl::TextureFormat::rgba32f, kWidth, kHeight, input);
  gl::Texture display = gl::Texture::create_2d(format, kWidth, kHeight);
  DisplayEncoder encoder;
  encoder.encode(radiance, stage, display);
  const std::vector<float> out = display.read();
  const int bits = format == gl::TextureFormat::rgba8 ? 8 : 16;
  const double top = bits == 8 ? 255.0 : 65535.0;
  int worst = 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(kWidth) * kHeight; ++i) {
    for (int c = 0; c < 3; ++c) {
      const float p = cpu_display_linear(input[4 * i + static_cast<std::size_t>(c)], stage, mask.alpha[i], c);
      const int expected = image::display_code(p, stage.encoding, bits);
      const int got = static_cast<int>(std::lround(out[4 * i + static_cast<std::size_t>(c)] * top));
      worst = std::max(worst, std::abs(got - expected));
    }
    EXPECT_EQ(out[4 * i + 3], 1.0f);
  }
  return worst;
}

TEST(DisplayEncoder, EqualsTheCpuPathWithinOneCodeIn8And16Bits) {
  const OutputStage plain;  // exponential, no output stage, sRGB
  EXPECT_LE(worst_code_difference(plain, gl::TextureFormat::rgba8, ones()), 1);
  EXPECT_LE(worst_code_difference(plain, gl::TextureFormat::rgba16, ones()), 1);
  OutputStage clamp;
  clamp.tone = image::ToneMapping::clamp;
  EXPECT_LE(worst_code_difference(clamp, gl::TextureFormat::rgba8, ones()), 1);
}

TEST(DisplayEncoder, AppliesTheBlendMaskAndBlackLevelAsTheCpuOutputStage) {
  context();
  const warp::BlendMask mask = test_mask();
  const gl::Texture mask_texture = blend_mask_texture(mask);
  OutputStage stage = blended(mask_texture, 0.05);
  EXPECT_LE(worst_code_difference(stage, gl::TextureFormat::rgba8, mask), 1);
  EXPECT_LE(worst_code_difference(stage, gl::TextureFormat::rgba16, mask), 1);
  // A black level without a mask: α = 1.
  stage.blend_mask = nullptr;
  EXPECT_LE(worst_code_difference(stage, gl::TextureFormat::rgba8, ones()), 1);
}

TEST(DisplayEncoder, EncodesForAGammaDisplay) {
  OutputStage stage;
  stage.encoding = {image::DisplayEncoding::Transfer::gamma, 2.4};
  EXPECT_LE(worst_code_difference(stage, gl::TextureFormat::rgba8, ones()), 1);
  EXPECT_LE(worst_code_difference(stage, gl::TextureFormat::rgba16, ones()), 1);
  // Not the sRGB curve: mid grey (0.2 linear) is code 124 in sRGB, 130 at gamma 2.4.
  EXPECT_EQ(image::display_code(0.2f, stage.encoding, 8), 130);
  EXPECT_EQ(image::display_code(0.2f, {}, 8), 124);
}

TEST(DisplayEncoder, FadesTowardAColourBeforeTheOutputStage) {
  context();
  const warp::BlendMask mask = test_mask();
  const gl::Texture mask_texture = blend_mask_texture(mask);
  OutputStage stage = blended(mask_texture, 0.02);
  stage.fade = {0.5, {0.25, 0.0, 1.0}};
  EXPECT_LE(worst_code_difference(stage, gl::TextureFormat::rgba8, mask), 1);
  // Fully faded to black, every pixel shows the black level alone: β = 0.02 → sRGB code 39.
  stage.fade = {1.0, {0.0, 0.0, 0.0}};
  const gl::Texture radiance = gl::Texture::create_2d(gl::TextureFormat::rgba32f, kWidth, kHeight, test_radiance());
  gl::Texture display = gl::Texture::create_2d(gl::TextureFormat::rgba8, kWidth, kHeight);
  DisplayEncoder encoder;
  encoder.encode(radiance, stage, display);
  const std::vector<float> out = display.read();
  ASSERT_EQ(image::display_code(0.02f, {}, 8), 39);
  for (std::size_t i = 0; i < out.size(); ++i) ASSERT_EQ(std::lround(out[i] * 255.0), i % 4 == 3 ? 255 : 39) << i;
}

TEST(DisplayEncoder, RefusesBadTargetsAndValues) {
  context();
  const gl::Texture radiance = gl::Texture::create_2d(gl::TextureFormat::rgba32f, 8, 8);
  gl::Texture floats = gl::Texture::create_2d(gl::TextureFormat::rgba32f, 8, 8);
  gl::Texture small = gl::Texture::create_2d(gl::TextureFormat::rgba8, 4, 8);
  gl::Texture good = gl::Texture::create_2d(gl::TextureFormat::rgba8, 8, 8);
  DisplayEncoder encoder;
  EXPECT_THROW(encoder.encode(radiance, {}, floats), std::invalid_argument);
  EXPECT_THROW(encoder.encode(radiance, {}, small), std::invalid_argument);
  OutputStage bad_fade;
  bad_fade.fade.level = 1.5;
  EXPECT_THROW(encoder.encode(radiance, bad_fade, good), std::invalid_argument);
  OutputStage bad_gamma;
  bad_gamma.encoding = {image::DisplayEncoding::Transfer::gamma, 0.5};
  EXPECT_THROW(encoder.encode(radiance, bad_gamma, good), std::invalid_argument);
  EXPECT_THROW(encoder.thumbnail(radiance, {}, 65), std::invalid_argument);
}

TEST(DisplayEncoder, ThumbnailsAreBoxMeansOfTheDisplayLinearValues) {
  // 64 × 48 → 16 × 12 (edge 16): each thumbnail pixel the mean of a 4 × 4 box,
  // computed in double here; the GPU sums in float (16 terms: relative error
  // below 1e-6) and clamps each value to [0, 1] first.
  context();
  const warp::BlendMask mask = test_mask();
  const gl::Texture mask_texture = blend_mask_texture(mask);
  const OutputStage stage = blended(mask_texture, 0.1);
  const std::vector<float> input = test_radiance();
  const gl::Texture radiance = gl::Texture::create_2d(gl::TextureFormat::rgba32f, kWidth, kHeight, input);
  DisplayEncoder encoder;
  const ThumbnailMeans t = encoder.thumbnail(radiance, stage, 16);
  ASSERT_EQ(t.width_px, 16);
  ASSERT_EQ(t.height_px, 12);
  for (int ty = 0; ty < 12; ++ty)
    for (int tx = 0; tx < 16; ++tx)
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (int y = 4 * ty; y < 4 * ty + 4; ++y)
          for (int x = 4 * tx; x < 4 * tx + 4; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * kWidth + x;
            const float v = cpu_display_linear(input[4 * i + static_cast<std::size_t>(c)], stage, mask.alpha[i], c);
            sum += std::isnan(v) ? 0.0 : std::clamp(static_cast<double>(v), 0.0, 1.0);
          }
        EXPECT_NEAR(t.rgb[(static_cast<std::size_t>(ty) * 16 + tx) * 3 + static_cast<std::size_t>(c)], sum / 16.0, 2e-6)
            << tx << "," << ty << " channel " << c;
      }
  EXPECT_EQ(thumbnail_size(1920, 1080, 64), (std::array<int, 2>{64, 36}));
  EXPECT_EQ(thumbnail_size(30, 20, 64), (std::array<int, 2>{30, 20}));
}

}  // namespace
}  // namespace zenith::render::display
