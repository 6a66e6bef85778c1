// OpenEXR: writing linear frames and reading them (and other EXR layouts) back.
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfRgbaFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfTiledRgbaFile.h>

#include <Imath/half.h>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>

#include "image/image_io.h"
#include "image/image_writer.h"
#include "tests/image/image_test_util.h"

namespace zenith::image {
namespace {

using testing::TempDir;

/// ±m · 2^e, m in [0, 1), e in [min_exponent, max_exponent].
std::vector<float> random_values(int width, int height, std::uint32_t seed, int min_exponent = -20,
                                 int max_exponent = 20) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> mantissa(-1.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(min_exponent, max_exponent);
  std::vector<float> v(std::size_t(width) * height * 3);
  for (float& x : v) x = std::ldexp(mantissa(rng), exponent(rng));
  return v;
}

TEST(Exr, FloatRoundTripIsExact) {
  TempDir dir;
  const int w = 37, h = 23;
  std::vector<float> rgb = random_values(w, h, 1);
  rgb[0] = 0.0f;
  rgb[1] = -0.0f;
  rgb[2] = std::numeric_limits<float>::max();
  rgb[3] = std::numeric_limits<float>::denorm_min();
  write_exr(dir / "f.exr", w, h, rgb, ExrPixelType::float32);
  const LinearImage image = read_image(dir / "f.exr");
  ASSERT_EQ(image.width, w);
  ASSERT_EQ(image.height, h);
  ASSERT_EQ(image.rgb.size(), rgb.size());
  for (std::size_t k = 0; k < rgb.size(); ++k) ASSERT_EQ(image.rgb[k], rgb[k]) << k;
}

TEST(Exr, HalfRoundTripIsWithinHalfPrecision) {
  TempDir dir;
  const int w = 41, h = 19;
  std::vector<float> rgb = random_values(w, h, 2, -27, 16);  // the whole half range, subnormals included
  rgb[0] = 1e6f;                                             // beyond the half range: clamped to 65504
  rgb[1] = -70000.0f;                                        // and on the other side
  write_exr(dir / "h.exr", w, h, rgb, ExrPixelType::half);
  const LinearImage image = read_image(dir / "h.exr");
  ASSERT_EQ(image.rgb.size(), rgb.size());
  EXPECT_EQ(image.rgb[0], 65504.0f);
  EXPECT_EQ(image.rgb[1], -65504.0f);
  for (std::size_t k = 2; k < rgb.size(); ++k) {
    const float x = std::clamp(rgb[k], -65504.0f, 65504.0f);
    // Normal halves: relative error ≤ 2^-11 (round to nearest); subnormals: absolute ≤ 2^-25.
    const float bound = std::max(std::fabs(x) * std::ldexp(1.0f, -11), std::ldexp(1.0f, -25));
    ASSERT_NEAR(image.rgb[k], x, bound) << k;
    ASSERT_EQ(image.rgb[k], float(Imath::half(x))) << k;  // exactly the nearest half
  }
}

TEST(Exr, AttributesAndLayoutReadBack) {
  TempDir dir;
  const ImageAttributes attributes{
      {"zenith:scene", "earth-moon"}, {"zenith:units", "W m^-2 sr^-1 nm^-1 × exposure"}, {"zenith:empty", ""}};
  write_exr(dir / "a.exr", 4, 3, testing::test_pattern(4, 3), ExrPixelType::half, attributes);
  Imf::InputFile file((dir / "a.exr").c_str());
  const Imf::Header& header = file.header();
  for (const auto& [name, value] : attributes) {
    const auto* a = header.findTypedAttribute<Imf::StringAttribute>(name);
    ASSERT_NE(a, nullptr) << name;
    EXPECT_EQ(a->value(), value) << name;
  }
  EXPECT_EQ(header.compression(), Imf::ZIP_COMPRESSION);
  EXPECT_TRUE(Imf::hasChromaticities(header));
  for (const char* c : {"R", "G", "B"}) {
    ASSERT_NE(header.channels().findChannel(c), nullptr) << c;
    EXPECT_EQ(header.channels().findChannel(c)->type, Imf::HALF) << c;
  }
  const Imath::Box2i dw = header.dataWindow();
  EXPECT_EQ(dw.min, Imath::V2i(0, 0));
  EXPECT_EQ(dw.max, Imath::V2i(3, 2));
}

TEST(Exr, AttributeNamesTheWriterOwnsOrRepeatsAreRejected) {
  TempDir dir;
  const std::vector<float> rgb = testing::test_pattern(2, 2);
  EXPECT_THROW(write_exr(dir / "x.exr", 2, 2, rgb, ExrPixelType::half, {{"compression", "none"}}),
               std::invalid_argument);
  EXPECT_THROW(write_exr(dir / "x.exr", 2, 2, rgb, ExrPixelType::half, {{"a", "1"}, {"a", "2"}}),
               std::invalid_argument);
  EXPECT_THROW(write_exr(dir / "x.exr", 2, 2, rgb, ExrPixelType::half, {{"", "1"}}), std::invalid_argument);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Exr, PixelTypeNamesRoundTrip) {
  for (ExrPixelType t : {ExrPixelType::half, ExrPixelType::float32}) EXPECT_EQ(parse_exr_pixel_type(to_string(t)), t);
  EXPECT_THROW(parse_exr_pixel_type("double"), std::invalid_argument);
}

/// Writes an EXR with the given channels (each `type`), data window origin (x0, y0),
/// channel c of pixel (x, y) = value(c, x, y).
template <class Value>
void write_custom_exr(const std::filesystem::path& path, const std::vector<std::string>& channels, Imf::PixelType type,
                      int x0, int y0, int w, int h, Value value) {
  Imf::Header header(Imath::Box2i({x0, y0}, {x0 + w + 3, y0 + h + 3}),
                     Imath::Box2i({x0, y0}, {x0 + w - 1, y0 + h - 1}));
  for (const auto& c : channels) header.channels().insert(c, Imf::Channel(type));
  std::vector<std::vector<float>> f(channels.size(), std::vector<float>(std::size_t(w) * h));
  std::vector<std::vector<unsigned>> u(channels.size(), std::vector<unsigned>(std::size_t(w) * h));
  std::vector<std::vector<Imath::half>> hf(channels.size(), std::vector<Imath::half>(std::size_t(w) * h));
  Imf::FrameBuffer frame;  // OpenEXR writes only from frame buffers of the channels' own type
  for (std::size_t c = 0; c < channels.size(); ++c) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        f[c][std::size_t(y) * w + x] = value(int(c), x, y);
        u[c][std::size_t(y) * w + x] = unsigned(value(int(c), x, y));
        hf[c][std::size_t(y) * w + x] = Imath::half(value(int(c), x, y));
      }
    const Imath::Box2i dw = header.dataWindow();
    if (type == Imf::UINT)
      frame.insert(channels[c], Imf::Slice::Make(Imf::UINT, u[c].data(), dw));
    else if (type == Imf::HALF)
      frame.insert(channels[c], Imf::Slice::Make(Imf::HALF, hf[c].data(), dw));
    else
      frame.insert(channels[c], Imf::Slice::Make(Imf::FLOAT, f[c].data(), dw));
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(frame);
  file.writePixels(h);
}

TEST(Exr, ReadsGreyYChannelsUintPixelsAndOffsetDataWindows) {
  TempDir dir;
  const auto value = [](int c, int x, int y) { return float(10 * (c + 1) + x + 100 * y); };
  write_custom_exr(dir / "y.exr", {"Y"}, Imf::HALF, 0, 0, 5, 4, value);
  LinearImage grey = read_image(dir / "y.exr");
  ASSERT_EQ(grey.width, 5);
  ASSERT_EQ(grey.height, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(grey.rgb[(std::size_t(y) * 5 + x) * 3 + c], value(0, x, y));

  write_custom_exr(dir / "u.exr", {"B", "G", "R", "A"}, Imf::UINT, -7, 12, 6, 3, value);
  const LinearImage uints = read_image(dir / "u.exr");
  ASSERT_EQ(uints.width, 6);
  ASSERT_EQ(uints.height, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 6; ++x) {
      const float* p = &uints.rgb[(std::size_t(y) * 6 + x) * 3];
      EXPECT_EQ(p[0], value(2, x, y));  // R is the third channel written
      EXPECT_EQ(p[1], value(1, x, y));
      EXPECT_EQ(p[2], value(0, x, y));
    }
}

TEST(Exr, AMissingChannelIsNamed) {
  TempDir dir;
  const auto value = [](int, int x, int) { return float(x); };
  write_custom_exr(dir / "rb.exr", {"R", "B"}, Imf::FLOAT, 0, 0, 2, 2, value);
  testing::expect_throw_with<std::runtime_error>([&] { (void)read_image(dir / "rb.exr"); },
                                                 {(dir / "rb.exr").string(), "channel G is missing"});
  write_custom_exr(dir / "z.exr", {"Z", "A"}, Imf::FLOAT, 0, 0, 2, 2, value);
  testing::expect_throw_with<std::runtime_error>([&] { (void)read_image(dir / "z.exr"); },
                                                 {"no R, G, B or Y channel (channels: A, Z)"});
}

TEST(Exr, ReadsTiledAndMultiPartFiles) {
  TempDir dir;
  const int w = 20, h = 11;
  std::vector<Imf::Rgba> pixels(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) pixels[std::size_t(y) * w + x] = Imf::Rgba(float(x), float(y), float(x + y), 1.0f);
  {
    Imf::TiledRgbaOutputFile tiled((dir / "tiled.exr").c_str(), w, h, 8, 8, Imf::ONE_LEVEL, Imf::ROUND_DOWN,
                                   Imf::WRITE_RGBA);
    tiled.setFrameBuffer(pixels.data(), 1, w);
    tiled.writeTiles(0, tiled.numXTiles() - 1, 0, tiled.numYTiles() - 1);
  }
  {
    std::vector<Imf::Header> headers(2, Imf::Header(w, h));
    headers[0].setName("beauty");
    headers[1].setName("depth");
    for (const char* c : {"R", "G", "B"}) headers[0].channels().insert(c, Imf::Channel(Imf::HALF));
    headers[1].channels().insert("Z", Imf::Channel(Imf::HALF));
    for (auto& header : headers) header.setType(Imf::SCANLINEIMAGE);
    Imf::MultiPartOutputFile file((dir / "multi.exr").c_str(), headers.data(), 2);
    for (int part = 0; part < 2; ++part) {
      Imf::OutputPart out(file, part);
      Imf::FrameBuffer frame;
      const std::size_t xs = sizeof(Imf::Rgba), ys = xs * w;
      char* base = reinterpret_cast<char*>(pixels.data());
      if (part == 0) {
        frame.insert("R", Imf::Slice(Imf::HALF, base + offsetof(Imf::Rgba, r), xs, ys));
        frame.insert("G", Imf::Slice(Imf::HALF, base + offsetof(Imf::Rgba, g), xs, ys));
        frame.insert("B", Imf::Slice(Imf::HALF, base + offsetof(Imf::Rgba, b), xs, ys));
      } else {
        frame.insert("Z", Imf::Slice(Imf::HALF, base + offsetof(Imf::Rgba, a), xs, ys));
      }
      out.setFrameBuffer(frame);
      out.writePixels(h);
    }
  }
  for (const char* name : {"tiled.exr", "multi.exr"}) {
    SCOPED_TRACE(name);
    const LinearImage image = read_image(dir / name);
    ASSERT_EQ(image.width, w);
    ASSERT_EQ(image.height, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float* p = &image.rgb[(std::size_t(y) * w + x) * 3];
        ASSERT_EQ(p[0], float(x));
        ASSERT_EQ(p[1], float(y));
        ASSERT_EQ(p[2], float(x + y));
      }
  }
}

}  // namespace
}  // namespace zenith::image
