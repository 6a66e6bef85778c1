// 8/16-bit PNG and 16-bit TIFF frames from display codes (image/display_image_writer.h):
// the stored samples are exactly the codes given, whatever the compression; a full disk is an error naming the file.
#include <gtest/gtest.h>
#include <png.h>
#include <tiffio.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/display_image_writer.h"
#include "tests/image/image_test_util.h"

namespace zenith::image {
namespace {

using testing::TempDir;

template <typename T>
std::vector<T> random_rgba(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> code(0, int(std::numeric_limits<T>::max()));
  std::vector<T> v(std::size_t(w) * h * 4);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = T(i % 4 == 3 ? 0 : code(rng));  // alpha is dropped
  // A smooth ramp in the lower half, as skies are (the filters then matter).
  for (int y = h / 2; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        v[(std::size_t(y) * w + x) * 4 + c] = T((x * 3 + y + c) % (int(std::numeric_limits<T>::max()) + 1));
  return v;
}

/// The RGB samples of a PNG (8 or 16 bits, no transforms; 16-bit as stored, big endian, made native).
std::vector<std::uint16_t> png_samples(const std::filesystem::path& path, int& bits) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error("cannot open " + path.string());
  png_structp p = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(p);
  std::vector<std::uint16_t> out;
  if (setjmp(png_jmpbuf(p))) {
    png_destroy_read_struct(&p, &info, nullptr);
    std::fclose(f);
    throw std::runtime_error("libpng failed on " + path.string());
  }
  png_init_io(p, f);
  png_read_info(p, info);
  const int w = int(png_get_image_width(p, info)), h = int(png_get_image_height(p, info));
  bits = png_get_bit_depth(p, info);
  EXPECT_EQ(png_get_color_type(p, info), PNG_COLOR_TYPE_RGB);
  int intent = 0;
  EXPECT_NE(png_get_sRGB(p, info, &intent), 0u) << "an sRGB chunk";
  std::vector<unsigned char> row(std::size_t(w) * 3 * (bits / 8));
  for (int y = 0; y < h; ++y) {
    png_read_row(p, row.data(), nullptr);
    for (std::size_t k = 0; k < std::size_t(w) * 3; ++k)
      out.push_back(bits == 8 ? row[k] : std::uint16_t(row[2 * k] << 8 | row[2 * k + 1]));
  }
  png_read_end(p, info);
  png_destroy_read_struct(&p, &info, nullptr);
  std::fclose(f);
  return out;
}

template <typename T>
std::vector<std::uint16_t> rgb_of(const std::vector<T>& rgba) {
  std::vector<std::uint16_t> rgb;
  for (std::size_t i = 0; i < rgba.size(); ++i)
    if (i % 4 != 3) rgb.push_back(rgba[i]);
  return rgb;
}

std::span<const std::byte> bytes_of(const auto& v) { return std::as_bytes(std::span(v)); }

TEST(DisplayWriter, PngStoresTheCodesAt8And16BitsAtEveryCompression) {
  TempDir dir;
  const int w = 37, h = 20;  // odd width: no row padding assumed
  const auto codes8 = random_rgba<std::uint8_t>(w, h, 1);
  const auto codes16 = random_rgba<std::uint16_t>(w, h, 2);
  for (const int level : {0, kFastPngCompression, kDefaultPngCompression, 9}) {
    int bits = 0;
    const auto p8 = dir.path() / ("f8-" + std::to_string(level) + ".png");
    write_png_display(p8, w, h, 8, bytes_of(codes8), level, {{"zenith:frame", "3"}});
    EXPECT_EQ(png_samples(p8, bits), rgb_of(codes8)) << "level " << level;
    EXPECT_EQ(bits, 8);
    const auto p16 = dir.path() / ("f16-" + std::to_string(level) + ".png");
    write_png_display(p16, w, h, 16, bytes_of(codes16), level);
    EXPECT_EQ(png_samples(p16, bits), rgb_of(codes16)) << "level " << level;
    EXPECT_EQ(bits, 16);
  }
  EXPECT_EQ(testing::read_written_png(dir.path() / "f8-1.png").text,
            (std::vector<std::pair<std::string, std::string>>{{"zenith:frame", "3"}}));
  EXPECT_THROW(write_png_display(dir.path() / "x.png", w, h, 12, bytes_of(codes16), 1), std::invalid_argument);
  EXPECT_THROW(write_png_display(dir.path() / "x.png", w, h, 8, bytes_of(codes8), 10), std::invalid_argument);
  EXPECT_THROW(write_png_display(dir.path() / "x.png", w, h + 1, 8, bytes_of(codes8), 1), std::invalid_argument);
  EXPECT_EQ(parse_png_compression("fast"), 1);
  EXPECT_EQ(parse_png_compression("default"), 6);
  EXPECT_EQ(parse_png_compression("best"), 9);
  EXPECT_EQ(parse_png_compression("4"), 4);
  EXPECT_THROW(parse_png_compression("10"), std::invalid_argument);
}

TEST(DisplayWriter, TiffStores16BitRgbCodesAndTheAttributes) {
  TempDir dir;
  const int w = 29, h = 19;  // strips of 8 rows: the last one short
  const auto codes = random_rgba<std::uint16_t>(w, h, 3);
  for (const TiffCompression c : {TiffCompression::none, TiffCompression::deflate, TiffCompression::lzw}) {
    const auto path = dir.path() / (std::string(to_string(c)) + ".tif");
    write_tiff16_display(path, w, h, codes, c, {{"zenith:scene", "earth"}, {"zenith:frame", "7"}});
    TIFF* t = TIFFOpen(path.c_str(), "r");
    ASSERT_NE(t, nullptr);
    std::uint32_t tw = 0, th = 0;
    std::uint16_t spp = 0, bps = 0;
    char* description = nullptr;
    TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &tw);
    TIFFGetField(t, TIFFTAG_IMAGELENGTH, &th);
    TIFFGetField(t, TIFFTAG_SAMPLESPERPIXEL, &spp);
    TIFFGetField(t, TIFFTAG_BITSPERSAMPLE, &bps);
    ASSERT_EQ(TIFFGetField(t, TIFFTAG_IMAGEDESCRIPTION, &description), 1);
    EXPECT_EQ(std::string(description), "zenith:scene=earth\nzenith:frame=7\n");
    EXPECT_EQ(tw, std::uint32_t(w));
    EXPECT_EQ(th, std::uint32_t(h));
    EXPECT_EQ(spp, 3);
    EXPECT_EQ(bps, 16);
    std::vector<std::uint16_t> samples, row(std::size_t(w) * 3);
    for (int y = 0; y < h; ++y) {
      ASSERT_EQ(TIFFReadScanline(t, row.data(), std::uint32_t(y)), 1);
      samples.insert(samples.end(), row.begin(), row.end());
    }
    TIFFClose(t);
    EXPECT_EQ(samples, rgb_of(codes)) << to_string(c);
  }
  EXPECT_EQ(parse_tiff_compression("lzw"), TiffCompression::lzw);
  EXPECT_THROW(parse_tiff_compression("jpeg"), std::invalid_argument);
}

/// A full disk: NAME.partial is a link to /dev/full, where every write fails with ENOSPC.
TEST(DisplayWriter, AFullDiskIsAnErrorNamingTheFileAndLeavesNothing) {
  TempDir dir;
  const int w = 256, h = 256;  // more than the stdio and libtiff buffers
  const auto codes8 = random_rgba<std::uint8_t>(w, h, 4);
  const auto codes16 = random_rgba<std::uint16_t>(w, h, 5);
  const auto expect_full = [&](const std::filesystem::path& path, const auto& write) {
    std::filesystem::path partial = path;
    partial += ".partial";
    std::filesystem::create_symlink("/dev/full", partial);
    try {
      write();
      FAIL() << path << " written to a full disk";
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
      EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
    }
    EXPECT_FALSE(std::filesystem::exists(path));
  };
  expect_full(dir.path() / "frame.png",
              [&] { write_png_display(dir.path() / "frame.png", w, h, 8, bytes_of(codes8), 0); });
  expect_full(dir.path() / "frame.tif",
              [&] { write_tiff16_display(dir.path() / "frame.tif", w, h, codes16, TiffCompression::none); });
}

}  // namespace
}  // namespace zenith::image
