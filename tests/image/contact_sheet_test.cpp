// Contact sheets: the box filter, the grid layout and the PNG written from rendered files.
#include <gtest/gtest.h>

#include <cmath>

#include "image/contact_sheet.h"
#include "image/image_io.h"
#include "image/image_writer.h"
#include "tests/image/image_test_util.h"

namespace zenith::image {
namespace {

using testing::TempDir;

/// A w × h image whose pixel (x, y) is (value(x, y), 2 · value, 3 · value).
LinearImage make_image(int w, int h, float (*value)(int, int)) {
  LinearImage image{w, h, std::vector<float>(std::size_t(w) * h * 3)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) image.rgb[(std::size_t(y) * w + x) * 3 + c] = value(x, y) * float(c + 1);
  return image;
}

LinearImage uniform(int w, int h, float v) {
  LinearImage image{w, h, std::vector<float>(std::size_t(w) * h * 3, v)};
  return image;
}

float red(const LinearImage& image, int x, int y) { return image.rgb[(std::size_t(y) * image.width + x) * 3]; }

TEST(DownscaleBox, IntegerFactorAveragesBlocks) {
  // 4 × 2 → 2 × 1: each output pixel is the mean of a 2 × 2 block.
  const LinearImage image = make_image(4, 2, [](int x, int y) { return float(x + 10 * y); });
  const LinearImage small = downscale_box(image, 2, 1);
  ASSERT_EQ(small.width, 2);
  ASSERT_EQ(small.height, 1);
  EXPECT_FLOAT_EQ(red(small, 0, 0), (0 + 1 + 10 + 11) / 4.0f);
  EXPECT_FLOAT_EQ(red(small, 1, 0), (2 + 3 + 12 + 13) / 4.0f);
  EXPECT_FLOAT_EQ(small.rgb[2], 3.0f * (0 + 1 + 10 + 11) / 4.0f);  // blue = 3 · red
}

TEST(DownscaleBox, FractionalFactorWeighsPartlyCoveredPixels) {
  // 3 → 2 pixels: output 0 covers [0, 1.5): pixel 0 fully, pixel 1 half.
  const LinearImage image = make_image(3, 1, [](int x, int) { return float(3 * x); });  // 0, 3, 6
  const LinearImage small = downscale_box(image, 2, 1);
  EXPECT_NEAR(red(small, 0, 0), (0.0 * 1.0 + 3.0 * 0.5) / 1.5, 1e-6);  // 1
  EXPECT_NEAR(red(small, 1, 0), (3.0 * 0.5 + 6.0 * 1.0) / 1.5, 1e-6);  // 5
}

TEST(DownscaleBox, KeepsTheMeanOfTheImage) {
  const LinearImage image =
      make_image(37, 23, [](int x, int y) { return std::sin(0.3f * float(x)) + 0.1f * float(y); });
  const LinearImage small = downscale_box(image, 5, 4);
  double big_sum = 0.0, small_sum = 0.0;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) big_sum += image.rgb[i];
  for (std::size_t i = 0; i < small.rgb.size(); i += 3) small_sum += small.rgb[i];
  EXPECT_NEAR(small_sum / (5 * 4), big_sum / (37 * 23), 1e-5);
}

TEST(DownscaleBox, RejectsBadSizes) {
  EXPECT_THROW(downscale_box(uniform(4, 4, 0.5f), 0, 2), std::invalid_argument);
  EXPECT_THROW(downscale_box(LinearImage{}, 2, 2), std::invalid_argument);
  LinearImage short_data = uniform(4, 4, 0.5f);
  short_data.rgb.pop_back();
  EXPECT_THROW(downscale_box(short_data, 2, 2), std::invalid_argument);
}

TEST(ContactSheet, PlacesFramesInAGridWithTheirOutputsSideBySide) {
  // 5 frames of two outputs (16×16 and 32×16), cells 8 px high, 2 columns, 1 px gaps.
  std::vector<std::vector<LinearImage>> frames;
  for (int k = 0; k < 5; ++k) frames.push_back({uniform(16, 16, 0.1f * float(k + 1)), uniform(32, 16, 0.9f)});
  ContactSheetOptions options;
  options.cell_height_px = 8;
  options.columns = 2;
  options.gap_px = 1;
  options.background = 0.25f;
  const LinearImage sheet = compose_contact_sheet(frames, options);
  // A cell: 8 + 1 + 16 = 25 px wide; 2 columns: 1 + 25 + 1 + 25 + 1; 3 rows: 1 + 3 · (8 + 1).
  EXPECT_EQ(sheet.width, 53);
  EXPECT_EQ(sheet.height, 28);
  EXPECT_FLOAT_EQ(red(sheet, 0, 0), 0.25f);  // the gap
  EXPECT_FLOAT_EQ(red(sheet, 1, 1), 0.1f);   // frame 0, output 0
  EXPECT_FLOAT_EQ(red(sheet, 8, 8), 0.1f);
  EXPECT_FLOAT_EQ(red(sheet, 9, 1), 0.25f);    // between the outputs
  EXPECT_FLOAT_EQ(red(sheet, 10, 1), 0.9f);    // frame 0, output 1
  EXPECT_FLOAT_EQ(red(sheet, 27, 1), 0.2f);    // frame 1 starts at 1 + 25 + 1
  EXPECT_FLOAT_EQ(red(sheet, 1, 10), 0.3f);    // frame 2: second row, at 1 + 9
  EXPECT_FLOAT_EQ(red(sheet, 1, 19), 0.5f);    // frame 4: third row
  EXPECT_FLOAT_EQ(red(sheet, 27, 19), 0.25f);  // no frame 5: background
}

TEST(ContactSheet, AutomaticColumnsGiveASquarishSheet) {
  std::vector<std::vector<LinearImage>> frames(24, std::vector<LinearImage>{uniform(64, 64, 0.5f)});
  ContactSheetOptions options;
  options.cell_height_px = 10;
  options.gap_px = 0;
  const LinearImage sheet = compose_contact_sheet(frames, options);
  // round(sqrt(24)) = 5 columns, 5 rows.
  EXPECT_EQ(sheet.width, 50);
  EXPECT_EQ(sheet.height, 50);
}

TEST(ContactSheet, RejectsEmptyInput) {
  EXPECT_THROW(compose_contact_sheet({}), std::invalid_argument);
  EXPECT_THROW(compose_contact_sheet({{}}), std::invalid_argument);
  ContactSheetOptions bad;
  bad.cell_height_px = 0;
  EXPECT_THROW(compose_contact_sheet({{uniform(4, 4, 0.5f)}}, bad), std::invalid_argument);
}

TEST(ContactSheet, WritesAPngFromPngAndExrFiles) {
  TempDir dir;
  // A PNG of display value 0.5 (clamp: stored as is) and an EXR of radiance ln 2 (exponential: 1 − e^−x = 0.5).
  write_png(dir / "a.png", 20, 10, std::vector<float>(20 * 10 * 3, 0.5f), ToneMapping::clamp);
  write_exr(dir / "b.exr", 10, 10, std::vector<float>(10 * 10 * 3, std::log(2.0f)), ExrPixelType::float32);
  ContactSheetOptions options;
  options.cell_height_px = 5;
  options.gap_px = 2;
  const auto [w, h] = write_contact_sheet(dir / "sheet.png", {{dir / "a.png", dir / "b.exr"}, {dir / "a.png"}},
                                          ToneMapping::exponential, options);
  // round(sqrt(2 · 5 / 17)) = 1 column: cells of 10 + 2 + 5 px, two rows.
  EXPECT_EQ(w, 2 + 17 + 2);
  EXPECT_EQ(h, 2 + 5 + 2 + 5 + 2);
  const LinearImage sheet = read_image(dir / "sheet.png");
  ASSERT_EQ(sheet.width, w);
  ASSERT_EQ(sheet.height, h);
  // 0.5 display-linear comes back within one 8-bit sRGB step.
  EXPECT_NEAR(red(sheet, 2, 2), 0.5f, 0.004f);
  EXPECT_NEAR(red(sheet, 14, 2), 0.5f, 0.004f);  // the EXR, tone mapped
  EXPECT_NEAR(red(sheet, 0, 0), 0.0f, 1e-6f);    // background
  EXPECT_NEAR(red(sheet, 14, 9), 0.0f, 1e-6f);   // frame 1 has no second image
  EXPECT_FALSE(std::filesystem::exists(dir / "sheet.png.partial"));
  EXPECT_THROW(write_contact_sheet(dir / "x.png", {{dir / "missing.png"}}, ToneMapping::exponential),
               std::runtime_error);
}

TEST(ContactSheet, MosaicCellsPutTheTilesOfADomeMasterBackTogether) {
  TempDir dir;
  // Four 4 × 4 quadrants of an 8 × 8 picture, each its own value; one frame, cells 8 px high.
  const float values[4] = {0.1f, 0.3f, 0.6f, 0.9f};
  std::vector<MosaicTile> tiles;
  for (int q = 0; q < 4; ++q) {
    const auto file = dir / ("q" + std::to_string(q) + ".png");
    write_png(file, 4, 4, std::vector<float>(4 * 4 * 3, values[q]), ToneMapping::clamp);
    tiles.push_back({file, (q % 2) * 4, (q / 2) * 4});
  }
  ContactSheetOptions options;
  options.cell_height_px = 8;
  options.gap_px = 1;
  options.columns = 1;
  const auto [w, h] = write_mosaic_contact_sheet(dir / "sheet.png", {tiles}, ToneMapping::exponential, options);
  EXPECT_EQ(w, 1 + 8 + 1);
  EXPECT_EQ(h, 1 + 8 + 1);
  const LinearImage sheet = read_image(dir / "sheet.png");
  for (int q = 0; q < 4; ++q) {
    const int x = 1 + (q % 2) * 4 + 2, y = 1 + (q / 2) * 4 + 2;
    EXPECT_NEAR(red(sheet, x, y), values[q], 0.004f) << "quadrant " << q;
  }
  EXPECT_THROW(write_mosaic_contact_sheet(dir / "x.png", {{{dir / "q0.png", -1, 0}}}, ToneMapping::exponential),
               std::invalid_argument);
}

TEST(EvenlySpacedFrames, SpansTheRangeWithBothEnds) {
  const std::vector<std::uint64_t> f = evenly_spaced_frames(10, 109, 24);
  ASSERT_EQ(f.size(), 24u);
  EXPECT_EQ(f.front(), 10u);
  EXPECT_EQ(f.back(), 109u);
  EXPECT_EQ(f[1], 10u + 4u);  // round(99 / 23) = 4
  for (std::size_t i = 1; i < f.size(); ++i) EXPECT_GT(f[i], f[i - 1]);
}

TEST(EvenlySpacedFrames, SmallRangesAndEdgeCases) {
  EXPECT_EQ(evenly_spaced_frames(0, 4, 24), (std::vector<std::uint64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(evenly_spaced_frames(0, 4, 3), (std::vector<std::uint64_t>{0, 2, 4}));
  EXPECT_EQ(evenly_spaced_frames(7, 9, 1), (std::vector<std::uint64_t>{7}));
  EXPECT_TRUE(evenly_spaced_frames(5, 4, 3).empty());
  EXPECT_TRUE(evenly_spaced_frames(0, 4, 0).empty());
  const std::uint64_t big = std::uint64_t{1} << 62;
  EXPECT_EQ(evenly_spaced_frames(0, big, 3), (std::vector<std::uint64_t>{0, big / 2, big}));
}

}  // namespace
}  // namespace zenith::image
