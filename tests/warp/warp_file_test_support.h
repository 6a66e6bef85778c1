#pragma once
// Helpers shared by the warp-file tests: a scratch folder, hand-made PFMs and
// PNGs, checks of error messages, and a capture of logged warnings.
#include <gtest/gtest.h>
#include <png.h>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include <unistd.h>
#include <atomic>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "core/json_reader.h"

namespace zenith::warp::testing {

/// A fresh folder under the system's temp folder, removed with its contents.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag) {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("zenith_" + tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

  std::filesystem::path write(const std::string& name, const std::string& bytes) const {
    const std::filesystem::path file = path_ / name;
    std::ofstream stream(file, std::ios::binary);
    stream.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return file;
  }

 private:
  std::filesystem::path path_;
};

/// Runs `action`, expects it to throw a std::exception whose message contains
/// every one of `parts`.
inline void expect_error(const std::function<void()>& action, const std::vector<std::string>& parts) {
  try {
    action();
    ADD_FAILURE() << "no exception; expected one mentioning '" << parts.front() << "'";
  } catch (const std::exception& error) {
    const std::string message = error.what();
    for (const std::string& part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << "message: " << message << "\nmissing: " << part;
  }
}

/// Runs `action`, expects it to throw a zenith::ConfigError in `file` at the
/// JSON pointer `pointer` whose message contains `reason`.
inline void expect_config_error(const std::function<void()>& action, const std::string& file,
                                const std::string& pointer, const std::string& reason) {
  try {
    action();
    ADD_FAILURE() << "accepted; expected an error at " << pointer << ": " << reason;
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.file(), file) << message;
    EXPECT_EQ(e.key(), pointer) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message << "\nmissing: " << reason;
  }
}

/// Collects what is logged at level warn (or above) through spdlog's default
/// logger while it lives (the warp loaders' warnings), and restores the logger.
class LogCapture {
 public:
  LogCapture() : sink_(std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(256)), previous_(spdlog::default_logger()) {
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("capture", sink_));
  }
  ~LogCapture() { spdlog::set_default_logger(previous_); }
  LogCapture(const LogCapture&) = delete;
  LogCapture& operator=(const LogCapture&) = delete;

  /// The messages logged at warn or above, oldest first.
  std::vector<std::string> warnings() const {
    std::vector<std::string> out;
    for (const auto& message : sink_->last_raw())
      if (message.level >= spdlog::level::warn) out.emplace_back(message.payload.data(), message.payload.size());
    return out;
  }
  /// The one warning that contains every one of `parts`; fails the test when
  /// there is none.
  std::string expect_warning(const std::vector<std::string>& parts) const {
    for (const std::string& warning : warnings()) {
      bool all = true;
      for (const std::string& part : parts) all = all && warning.find(part) != std::string::npos;
      if (all) return warning;
    }
    std::string logged;
    for (const std::string& warning : warnings()) logged += "\n  " + warning;
    ADD_FAILURE() << "no warning mentions '" << parts.front() << "'; logged:" << logged;
    return {};
  }

 private:
  std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt> sink_;
  std::shared_ptr<spdlog::logger> previous_;
};

/// A PFM with `channels` channels; `value(x, y, c)` gives the sample of the
/// pixel at column x, row y counted from the top. `stored_top_first` writes the
/// top row first (MPCDI), else the bottom row first (classic PFM).
inline std::string make_pfm(int width, int height, int channels, const std::function<float(int, int, int)>& value,
                            bool little_endian, bool stored_top_first) {
  std::string bytes = std::string(channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(width) + " " +
                      std::to_string(height) + "\n" + (little_endian ? "-1.0" : "1.0") + "\n";
  for (int stored = 0; stored < height; ++stored) {
    const int y = stored_top_first ? stored : height - 1 - stored;
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) {
        std::uint32_t word = std::bit_cast<std::uint32_t>(value(x, y, c));
        unsigned char b[4];
        for (int k = 0; k < 4; ++k) b[k] = static_cast<unsigned char>(word >> (8 * k));  // little endian
        if (!little_endian) std::swap(b[0], b[3]), std::swap(b[1], b[2]);
        bytes.append(reinterpret_cast<const char*>(b), 4);
      }
  }
  return bytes;
}

/// A grey PNG (libpng's simplified API): 8-bit for unsigned char samples,
/// 16-bit for std::uint16_t ones; width · height samples, row 0 at the top.
template <typename Sample>
std::string make_grey_png(int width, int height, const std::vector<Sample>& grey) {
  static_assert(std::is_same_v<Sample, unsigned char> || std::is_same_v<Sample, std::uint16_t>);
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = sizeof(Sample) == 1 ? PNG_FORMAT_GRAY : PNG_FORMAT_LINEAR_Y;
  png_alloc_size_t size = 0;
  EXPECT_TRUE(png_image_write_to_memory(&image, nullptr, &size, 0, grey.data(), 0, nullptr));
  std::string bytes(size, '\0');
  EXPECT_TRUE(png_image_write_to_memory(&image, bytes.data(), &size, 0, grey.data(), 0, nullptr));
  bytes.resize(size);
  return bytes;
}

/// An 8-bit RGB PNG: width · height · 3 samples, row 0 at the top.
inline std::string make_rgb_png(int width, int height, const std::vector<unsigned char>& rgb) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  EXPECT_TRUE(png_image_write_to_memory(&image, nullptr, &size, 0, rgb.data(), 0, nullptr));
  std::string bytes(size, '\0');
  EXPECT_TRUE(png_image_write_to_memory(&image, bytes.data(), &size, 0, rgb.data(), 0, nullptr));
  bytes.resize(size);
  return bytes;
}

}  // namespace zenith::warp::testing
