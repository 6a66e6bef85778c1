// PNG in memory (image/png_encoder.h): the bytes read back as the pixels they
// were made of, and the size checks.
#include "image/png_encoder.h"

#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>
#include <vector>

#include "image/image_io.h"
#include "image/tone_mapping.h"
#include "tests/image/image_test_util.h"

namespace zenith::image {
namespace {

using testing::TempDir;

TEST(PngEncoder, ReadsBackAsThePixelsItWasMadeOf) {
  TempDir dir;
  const int w = 5, h = 3;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<std::uint8_t>(i * 17);
  const std::vector<std::uint8_t> png = encode_png_rgb8(w, h, rgb);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png[1], 'P');
  EXPECT_EQ(png[2], 'N');
  EXPECT_EQ(png[3], 'G');
  const auto path = dir / "memory.png";
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  const LinearImage back = read_image(path);
  ASSERT_EQ(back.width, w);
  ASSERT_EQ(back.height, h);
  for (std::size_t i = 0; i < rgb.size(); ++i) EXPECT_EQ(display_byte(back.rgb[i], ToneMapping::clamp), rgb[i]) << i;
}

TEST(PngEncoder, RefusesWrongSizes) {
  EXPECT_THROW(encode_png_rgb8(0, 1, {}), std::invalid_argument);
  EXPECT_THROW(encode_png_rgb8(40000, 1, {}), std::invalid_argument);
  const std::vector<std::uint8_t> six(6);
  EXPECT_THROW(encode_png_rgb8(2, 2, six), std::invalid_argument);
  EXPECT_NO_THROW(encode_png_rgb8(2, 1, six));
}

}  // namespace
}  // namespace zenith::image
