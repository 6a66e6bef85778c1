// PNG: tone-mapped 8-bit sRGB previews, reading every PNG layout back to linear, and 16-bit grey maps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "image/image_writer.h"
#include "image/tone_mapping.h"
#include "tests/image/image_test_util.h"

namespace zenith::image {
namespace {

using testing::TempDir;

/// Values covering the operators' whole range, specials included.
std::vector<float> preview_values(int count) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> v(std::size_t(count) * 3);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = std::pow(u(rng), 3.0f) * 6.0f;
  v[0] = 0.0f;
  v[1] = -2.0f;
  v[2] = std::numeric_limits<float>::quiet_NaN();
  v[3] = std::numeric_limits<float>::infinity();
  v[4] = 0.0031308f;
  v[5] = 1.0f;
  return v;
}

TEST(Png, BytesAreTheToneMappedSrgbFormula) {
  TempDir dir;
  const int w = 64, h = 48;
  const std::vector<float> rgb = preview_values(w * h);
  for (ToneMapping tone : {ToneMapping::exponential, ToneMapping::clamp}) {
    const auto path = dir / (std::string(to_string(tone)) + ".png");
    write_png(path, w, h, rgb, tone);
    const testing::WrittenPng png = testing::read_written_png(path);
    ASSERT_EQ(png.width, w);
    ASSERT_EQ(png.height, h);
    EXPECT_TRUE(png.has_srgb_chunk);
    for (std::size_t k = 0; k < rgb.size(); ++k)
      ASSERT_EQ(png.bytes[k], display_byte(rgb[k], tone)) << k << " " << rgb[k];
  }
}

TEST(Png, ReadBackDecodesToLinearWithinHalfACodeStep) {
  TempDir dir;
  const int w = 50, h = 20;
  const std::vector<float> rgb = preview_values(w * h);
  for (ToneMapping tone : {ToneMapping::exponential, ToneMapping::clamp}) {
    write_png(dir / "p.png", w, h, rgb, tone);
    const LinearImage image = read_image(dir / "p.png");
    ASSERT_EQ(image.width, w);
    ASSERT_EQ(image.height, h);
    for (std::size_t k = 0; k < rgb.size(); ++k) {
      // In sRGB space the read-back value is the written one rounded to 1/255.
      const float written = srgb_encode(tone_map(rgb[k], tone));
      ASSERT_NEAR(srgb_encode(image.rgb[k]), written, 0.5f / 255.0f + 1e-6f) << k;
      ASSERT_EQ(image.rgb[k], srgb_decode(float(display_byte(rgb[k], tone)) / 255.0f)) << k;
    }
  }
}

TEST(Png, AttributesBecomeTextChunks) {
  TempDir dir;
  const ImageAttributes attributes{{"zenith:scene", "earth-moon"}, {"Comment", "exposure 1.5e-5 × radiance"}};
  write_png(dir / "t.png", 3, 2, testing::test_pattern(3, 2), ToneMapping::exponential, attributes);
  const testing::WrittenPng png = testing::read_written_png(dir / "t.png");
  ASSERT_EQ(png.text.size(), 2u);
  EXPECT_EQ(png.text[0], attributes[0]);
  EXPECT_EQ(png.text[1], attributes[1]);
  // ASCII as tEXt, UTF-8 as iTXt.
  const std::vector<unsigned char> bytes = testing::read_bytes(dir / "t.png");
  const std::string file(bytes.begin(), bytes.end());
  EXPECT_NE(file.find(std::string("tEXtzenith:scene\0earth-moon", 27)), std::string::npos);
  EXPECT_NE(file.find("iTXtComment"), std::string::npos);
  EXPECT_EQ(file.find("tIME"), std::string::npos);
}

TEST(Png, KeywordsThatPngCannotStoreAreRejected) {
  TempDir dir;
  const std::vector<float> rgb = testing::test_pattern(2, 2);
  for (const std::string& key : {std::string(""), std::string(" lead"), std::string("two  spaces"),
                                 std::string(80, 'k'), std::string("caf\xc3\xa9")}) {
    EXPECT_THROW(write_png(dir / "k.png", 2, 2, rgb, ToneMapping::clamp, {{key, "v"}}), std::invalid_argument) << key;
  }
  EXPECT_THROW(write_png(dir / "k.png", 2, 2, rgb, ToneMapping::clamp, {{"nul", std::string("a\0b", 3)}}),
               std::invalid_argument);
  EXPECT_TRUE(dir.entries().empty());
}

/// Sample values for a layout: code(x, y, c) in [0, 2^depth), c < channels.
unsigned code(int x, int y, int c, int depth) { return unsigned(x * 7 + y * 13 + c * 29 + x * y) % (1u << depth); }

/// Packs samples of `depth` bits, most significant first (PNG order).
std::vector<unsigned char> pack_row(const std::vector<unsigned>& samples, int depth) {
  std::vector<unsigned char> row;
  if (depth == 16) {
    for (unsigned s : samples)
      row.push_back(static_cast<unsigned char>(s >> 8)), row.push_back(static_cast<unsigned char>(s & 255));
    return row;
  }
  row.assign((samples.size() * depth + 7) / 8, 0);
  for (std::size_t i = 0; i < samples.size(); ++i)
    row[i * depth / 8] |= static_cast<unsigned char>(samples[i] << (8 - depth - (i * depth) % 8));
  return row;
}

int channels_of(int colour_type) {
  switch (colour_type) {
    case PNG_COLOR_TYPE_GRAY_ALPHA: return 2;
    case PNG_COLOR_TYPE_RGB: return 3;
    case PNG_COLOR_TYPE_RGB_ALPHA: return 4;
    default: return 1;  // grey, palette
  }
}

struct Layout {
  int colour_type, depth;
  bool interlaced;
};

TEST(Png, ReadsEveryLayoutAndDecodesSrgbExactly) {
  TempDir dir;
  const int w = 13, h = 9;
  const std::vector<Layout> layouts{{PNG_COLOR_TYPE_GRAY, 1, false},        {PNG_COLOR_TYPE_GRAY, 2, false},
                                    {PNG_COLOR_TYPE_GRAY, 4, false},        {PNG_COLOR_TYPE_GRAY, 8, false},
                                    {PNG_COLOR_TYPE_GRAY, 16, false},       {PNG_COLOR_TYPE_GRAY_ALPHA, 8, false},
                                    {PNG_COLOR_TYPE_GRAY_ALPHA, 16, false}, {PNG_COLOR_TYPE_RGB, 8, false},
                                    {PNG_COLOR_TYPE_RGB, 16, false},        {PNG_COLOR_TYPE_RGB_ALPHA, 8, false},
                                    {PNG_COLOR_TYPE_RGB_ALPHA, 16, false},  {PNG_COLOR_TYPE_PALETTE, 4, false},
                                    {PNG_COLOR_TYPE_PALETTE, 8, false},     {PNG_COLOR_TYPE_RGB, 8, true},
                                    {PNG_COLOR_TYPE_GRAY, 16, true},        {PNG_COLOR_TYPE_PALETTE, 2, true}};
  for (const Layout& layout : layouts) {
    SCOPED_TRACE("colour type " + std::to_string(layout.colour_type) + ", " + std::to_string(layout.depth) + " bit" +
                 (layout.interlaced ? ", interlaced" : ""));
    testing::RawPng raw;
    raw.width = w;
    raw.height = h;
    raw.bit_depth = layout.depth;
    raw.colour_type = layout.colour_type;
    raw.interlaced = layout.interlaced;
    const bool palette = layout.colour_type == PNG_COLOR_TYPE_PALETTE;
    if (palette)
      for (int i = 0; i < (1 << layout.depth); ++i)
        raw.palette.push_back(
            {static_cast<png_byte>(i * 17), static_cast<png_byte>(255 - i * 9), static_cast<png_byte>(i * 5 + 3)});
    const int channels = channels_of(layout.colour_type);
    for (int y = 0; y < h; ++y) {
      std::vector<unsigned> samples;
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < channels; ++c) samples.push_back(code(x, y, c, layout.depth));
      raw.rows.push_back(pack_row(samples, layout.depth));
    }
    ASSERT_TRUE(testing::write_raw_png(dir / "l.png", raw));
    const LinearImage image = read_image(dir / "l.png");
    ASSERT_EQ(image.width, w);
    ASSERT_EQ(image.height, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
          float expected = 0.0f;
          if (palette) {
            const png_color& p = raw.palette[code(x, y, 0, layout.depth)];
            expected = srgb_decode(float((c == 0 ? p.red : c == 1 ? p.green : p.blue) / 255.0));
          } else {
            const bool grey = !(layout.colour_type & PNG_COLOR_MASK_COLOR);
            const unsigned v = code(x, y, grey ? 0 : c, layout.depth);
            expected = srgb_decode(float(double(v) / double((1u << layout.depth) - 1)));
          }
          ASSERT_EQ(image.rgb[(std::size_t(y) * w + x) * 3 + c], expected) << x << "," << y << "," << c;
        }
  }
}

TEST(Png, Grey16KeepsEverySampleAndStatesItsGamma) {
  TempDir dir;
  const int w = 300, h = 7;
  std::vector<std::uint16_t> grey(std::size_t(w) * h);
  for (std::size_t k = 0; k < grey.size(); ++k) grey[k] = std::uint16_t((k * 2311u) % 65536u);
  grey[0] = 0;
  grey[1] = 65535;
  for (const double gamma : {1.0, 2.2}) {
    write_png_grey16(dir / "m.png", w, h, grey, gamma, {{"zenith:map", "blend mask"}});
    const testing::WrittenPng png = testing::read_written_png(dir / "m.png");
    EXPECT_EQ(png.width, w);
    EXPECT_EQ(png.height, h);
    EXPECT_EQ(png.bit_depth, 16);
    EXPECT_EQ(png.colour_type, PNG_COLOR_TYPE_GRAY);
    EXPECT_NEAR(png.file_gamma, 1.0 / gamma, 1e-5);
    EXPECT_EQ(png.grey, grey);
    EXPECT_EQ(png.text, (ImageAttributes{{"zenith:map", "blend mask"}}));
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"m.png"});  // no .partial left
  EXPECT_THROW(write_png_grey16(dir / "n.png", w, h, std::span(grey).first(10), 1.0), std::invalid_argument);
  EXPECT_THROW(write_png_grey16(dir / "n.png", w, h, grey, 0.0), std::invalid_argument);
  try {
    write_png_grey16(dir / "no" / "n.png", w, h, grey, 1.0);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "no" / "n.png").string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace zenith::image
