#pragma once
// Shared by the image tests: a scratch directory, whole-file I/O, and raw PNG
// files written and read with libpng (bytes as they are, no colour handling).
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace zenith::image::testing {

/// A fresh directory under the system temp directory, removed with its contents.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("zenith-image-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
             (test ? std::string(test->name()) : std::string("x")));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }
  /// Every entry's file name, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(path_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  std::filesystem::path path_;
};

/// Runs `action` and expects it to throw an `Error` whose message contains
/// every one of `parts` (another exception fails the test as it propagates).
template <class Error>
void expect_throw_with(const std::function<void()>& action, const std::vector<std::string>& parts) {
  try {
    action();
    ADD_FAILURE() << "no exception; expected one mentioning '" << parts.front() << "'";
  } catch (const Error& e) {
    const std::string message = e.what();
    for (const std::string& part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << "message: " << message << "\nmissing: " << part;
  }
}

inline std::vector<unsigned char> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes, std::size_t count) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(count));
}
inline void write_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  write_bytes(path, bytes, bytes.size());
}

/// A PNG as stored: IHDR fields and the packed rows (bit depths below 8 packed
/// as PNG packs them, 16-bit samples big endian).
struct RawPng {
  int width = 0, height = 0, bit_depth = 8, colour_type = PNG_COLOR_TYPE_RGB;
  bool interlaced = false;
  std::vector<png_color> palette;
  std::vector<std::vector<unsigned char>> rows;
};

/// An 8-bit, non-interlaced image of `channels` (1: grey, 3: RGB) that is black.
inline RawPng black_raw_png(int width, int height, int channels) {
  RawPng png;
  png.width = width;
  png.height = height;
  png.colour_type = channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB;
  png.rows.assign(static_cast<std::size_t>(height),
                  std::vector<unsigned char>(static_cast<std::size_t>(width * channels), 0));
  return png;
}

/// Writes `png` with libpng, no transforms. Returns false on a libpng error.
inline bool write_raw_png(const std::filesystem::path& path, const RawPng& png) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  png_structp p = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(p);
  std::vector<png_bytep> rows;
  for (const auto& r : png.rows) rows.push_back(const_cast<png_bytep>(r.data()));
  volatile bool ok = false;  // set after setjmp, read after a longjmp
  if (!setjmp(png_jmpbuf(p))) {
    png_init_io(p, f);
    png_set_IHDR(p, info, png_uint_32(png.width), png_uint_32(png.height), png.bit_depth, png.colour_type,
                 png.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (!png.palette.empty()) png_set_PLTE(p, info, png.palette.data(), int(png.palette.size()));
    png_write_info(p, info);
    png_write_image(p, rows.data());
    png_write_end(p, nullptr);
    ok = true;
  }
  png_destroy_write_struct(&p, &info);
  std::fclose(f);
  return ok;
}

/// Reads an 8-bit RGB or a 16-bit grey PNG's samples and its text chunks
/// (keyword → text) with libpng, no transforms.
struct WrittenPng {
  int width = 0, height = 0, bit_depth = 0, colour_type = 0;
  bool has_srgb_chunk = false;
  double file_gamma = 0.0;           ///< the gAMA chunk's value, 0 when absent
  std::vector<unsigned char> bytes;  ///< 8-bit RGB: width · height · 3
  std::vector<std::uint16_t> grey;   ///< 16-bit grey: width · height
  std::vector<std::pair<std::string, std::string>> text;
};
inline WrittenPng read_written_png(const std::filesystem::path& path) {
  WrittenPng out;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error("cannot open " + path.string());
  png_structp p = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(p);
  volatile bool ok = false;  // set after setjmp, read after a longjmp
  if (!setjmp(png_jmpbuf(p))) {
    png_init_io(p, f);
    png_read_info(p, info);
    out.width = int(png_get_image_width(p, info));
    out.height = int(png_get_image_height(p, info));
    out.bit_depth = png_get_bit_depth(p, info);
    out.colour_type = png_get_color_type(p, info);
    int intent = 0;
    out.has_srgb_chunk = png_get_sRGB(p, info, &intent) != 0;
    if (png_get_valid(p, info, PNG_INFO_gAMA)) png_get_gAMA(p, info, &out.file_gamma);
    const bool rgb8 = out.bit_depth == 8 && out.colour_type == PNG_COLOR_TYPE_RGB;
    const bool grey16 = out.bit_depth == 16 && out.colour_type == PNG_COLOR_TYPE_GRAY;
    if (rgb8 || grey16) {
      const std::size_t row_bytes = std::size_t(out.width) * (rgb8 ? 3 : 2);
      std::vector<unsigned char> rows(row_bytes * out.height);
      for (int y = 0; y < out.height; ++y) png_read_row(p, rows.data() + std::size_t(y) * row_bytes, nullptr);
      if (rgb8) {
        out.bytes = std::move(rows);
      } else {
        for (std::size_t k = 0; k + 1 < rows.size(); k += 2)
          out.grey.push_back(std::uint16_t(rows[k] << 8 | rows[k + 1]));  // big endian
      }
      png_read_end(p, info);
      png_textp text = nullptr;
      const int n = png_get_text(p, info, &text, nullptr);
      for (int i = 0; i < n; ++i)
        out.text.emplace_back(
            text[i].key, std::string(text[i].text, text[i].text_length ? text[i].text_length : text[i].itxt_length));
      ok = true;
    }
  }
  png_destroy_read_struct(&p, &info, nullptr);
  std::fclose(f);
  if (!ok) throw std::runtime_error("not an 8-bit RGB or 16-bit grey PNG: " + path.string());
  return out;
}

/// Deterministic test values: a smooth ramp with some structure, in [0, scale].
inline std::vector<float> test_pattern(int width, int height, float scale = 4.0f) {
  std::vector<float> rgb(std::size_t(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        rgb[(std::size_t(y) * width + x) * 3 + c] =
            scale * float((x * 37 + y * 91 + c * 53) % 257) / 256.0f * (0.5f + 0.5f * float(c + 1) / 3.0f);
  return rgb;
}

}  // namespace zenith::image::testing
