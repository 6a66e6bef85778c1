// Streaming writers: chunked rows, atomic publication, misuse and bad pixels.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>

#include <cmath>
#include <functional>
#include <limits>

#include "image/image_io.h"
#include "image/image_writer.h"
#include "tests/image/image_test_util.h"

namespace zenith::image {
namespace {

using testing::TempDir;

struct Format {
  const char* name;
  std::function<std::unique_ptr<ImageWriter>(const std::filesystem::path&, int, int)> open;
};

std::vector<Format> formats() {
  return {{"exr-half",
           [](const auto& p, int w, int h) {
             return open_exr_writer(p, w, h, ExrPixelType::half, {{"k", "v"}});
           }},
          {"exr-float", [](const auto& p, int w, int h) { return open_exr_writer(p, w, h, ExrPixelType::float32); }},
          {"png", [](const auto& p, int w, int h) {
             return open_png_writer(p, w, h, ToneMapping::exponential, {{"k", "v"}});
           }}};
}

std::span<const float> rows(const std::vector<float>& rgb, int width, int first, int count) {
  return std::span<const float>(rgb).subspan(std::size_t(first) * width * 3, std::size_t(count) * width * 3);
}

/// Runs `check` on a 4 × 4 writer into `dir`/frame of every format, given
/// rows 0..2 of `rgb` (a test pattern 4 px wide, 4 or more rows).
void for_each_writer_missing_its_last_row(const TempDir& dir, const std::vector<float>& rgb,
                                          const std::function<void(std::unique_ptr<ImageWriter>&)>& check) {
  for (const Format& f : formats()) {
    SCOPED_TRACE(f.name);
    auto writer = f.open(dir / "frame", 4, 4);
    writer->write_rows(3, rows(rgb, 4, 0, 3));
    check(writer);
  }
}

TEST(ImageWriter, RowsInChunksGiveTheSameBytesAsOneWrite) {
  TempDir dir;
  const int w = 29, h = 83;  // several ZIP blocks of 16 rows, the last one partial
  const std::vector<float> rgb = testing::test_pattern(w, h);
  for (const Format& f : formats()) {
    SCOPED_TRACE(f.name);
    auto one = f.open(dir / "one", w, h);
    one->write_rows(h, rgb);
    one->finish();
    const std::vector<unsigned char> reference = testing::read_bytes(dir / "one");
    ASSERT_GT(reference.size(), 100u);
    for (const std::vector<int>& chunks : {std::vector<int>(h, 1), std::vector<int>{7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 6},
                                           std::vector<int>{16, 0, 16, 51}, std::vector<int>{33, 1, 2, 40, 7}}) {
      auto writer = f.open(dir / "chunked", w, h);
      int y = 0;
      for (int n : chunks) {
        writer->write_rows(n, rows(rgb, w, y, n));
        y += n;
      }
      ASSERT_EQ(y, h);
      writer->finish();
      ASSERT_EQ(testing::read_bytes(dir / "chunked"), reference) << chunks.size() << " chunks";
    }
  }
}

TEST(ImageWriter, WritesToAPartialFileAndRenamesItOnFinish) {
  TempDir dir;
  const int w = 8, h = 4;
  const std::vector<float> rgb = testing::test_pattern(w, h);
  for (const Format& f : formats()) {
    SCOPED_TRACE(f.name);
    testing::write_bytes(dir / "frame", {'o', 'l', 'd'});
    auto writer = f.open(dir / "frame", w, h);
    writer->write_rows(2, rows(rgb, w, 0, 2));
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"frame", "frame.partial"}));
    EXPECT_EQ(testing::read_bytes(dir / "frame").size(), 3u);  // the old file is untouched until finish
    writer->write_rows(2, rows(rgb, w, 2, 2));
    writer->finish();
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"frame"}));
    EXPECT_EQ(read_image(dir / "frame").width, w);
    writer.reset();  // destroying a finished writer keeps the file
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"frame"}));
    std::filesystem::remove(dir / "frame");
  }
}

TEST(ImageWriter, AWriterDestroyedBeforeFinishLeavesNoFile) {
  TempDir dir;
  const int w = 8, h = 40;
  const std::vector<float> rgb = testing::test_pattern(w, h);
  for (const Format& f : formats()) {
    SCOPED_TRACE(f.name);
    for (int written : {0, 1, 17, h}) {
      auto writer = f.open(dir / "frame", w, h);
      writer->write_rows(written, rows(rgb, w, 0, written));
      writer.reset();
      EXPECT_TRUE(dir.entries().empty()) << written << " rows";
    }
  }
}

TEST(ImageWriter, TooManyRowsIsALogicError) {
  TempDir dir;
  const std::vector<float> rgb = testing::test_pattern(4, 5);
  for_each_writer_missing_its_last_row(dir, rgb, [&](std::unique_ptr<ImageWriter>& writer) {
    testing::expect_throw_with<std::logic_error>([&] { writer->write_rows(2, rows(rgb, 4, 3, 2)); },
                                                 {"rows 3..4 written to a 4-row image"});
    writer->write_rows(1, rows(rgb, 4, 3, 1));  // the rejected call wrote nothing
    writer->finish();
    EXPECT_THROW(writer->write_rows(1, rows(rgb, 4, 0, 1)), std::logic_error);
    EXPECT_THROW(writer->finish(), std::logic_error);
    std::filesystem::remove(dir / "frame");
  });
}

TEST(ImageWriter, FinishWithMissingRowsThrowsAndPublishesNothing) {
  TempDir dir;
  for_each_writer_missing_its_last_row(dir, testing::test_pattern(4, 4), [&](std::unique_ptr<ImageWriter>& writer) {
    testing::expect_throw_with<std::logic_error>([&] { writer->finish(); }, {"3 of 4 rows"});
    writer.reset();
    EXPECT_TRUE(dir.entries().empty());
  });
}

TEST(ImageWriter, AWrongNumberOfValuesIsRejected) {
  TempDir dir;
  const std::vector<float> rgb = testing::test_pattern(4, 4);
  for (const Format& f : formats()) {
    SCOPED_TRACE(f.name);
    auto writer = f.open(dir / "frame", 4, 4);
    EXPECT_THROW(writer->write_rows(2, rows(rgb, 4, 0, 1)), std::invalid_argument);
    EXPECT_THROW(writer->write_rows(-1, {}), std::invalid_argument);
  }
  EXPECT_THROW(write_exr(dir / "x.exr", 4, 4, rows(rgb, 4, 0, 3), ExrPixelType::half), std::invalid_argument);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageWriter, InvalidSizesAreRejected) {
  TempDir dir;
  for (const Format& f : formats()) {
    SCOPED_TRACE(f.name);
    EXPECT_THROW(f.open(dir / "frame", 0, 4), std::invalid_argument);
    EXPECT_THROW(f.open(dir / "frame", 4, -1), std::invalid_argument);
    EXPECT_THROW(f.open(dir / "frame", 40000, 4), std::invalid_argument);
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageWriter, ExrRejectsNaNAndInfinityNamingThePixel) {
  TempDir dir;
  const int w = 6, h = 9;
  for (ExrPixelType type : {ExrPixelType::half, ExrPixelType::float32}) {
    SCOPED_TRACE(to_string(type));
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::infinity()}) {
      std::vector<float> rgb = testing::test_pattern(w, h);
      rgb[(std::size_t(5) * w + 3) * 3 + 1] = bad;  // pixel (3, 5), G
      auto writer = open_exr_writer(dir / "nan.exr", w, h, type);
      writer->write_rows(4, rows(rgb, w, 0, 4));
      testing::expect_throw_with<std::runtime_error>(
          [&] { writer->write_rows(5, rows(rgb, w, 4, 5)); },
          {"nan.exr", "pixel (x 3, y 5) channel G", std::isnan(bad) ? "NaN" : "infinite"});
      // Nothing of the rejected rows was written: the writer goes on with fixed values.
      rgb[(std::size_t(5) * w + 3) * 3 + 1] = 0.5f;
      writer->write_rows(5, rows(rgb, w, 4, 5));
      writer->finish();
      EXPECT_EQ(read_image(dir / "nan.exr").rgb[(std::size_t(5) * w + 3) * 3 + 1], 0.5f);
    }
  }
}

TEST(ImageWriter, AnUnwritableDirectoryIsARuntimeErrorNamingTheFile) {
  TempDir dir;
  const auto path = dir / "no" / "such" / "dir" / "frame.exr";
  for (const Format& f : formats()) {
    SCOPED_TRACE(f.name);
    testing::expect_throw_with<std::runtime_error>([&] { f.open(path, 4, 4); }, {path.string()});
  }
}

// A full disk during a live show once stopped the nodes with
// "error writing ….png.partial.partial" and no cause. A file-size limit
// (RLIMIT_FSIZE, SIGXFSZ ignored: writes fail with EFBIG) plays the full disk
// for this process alone; the message names the file and the cause.
TEST(ImageWriter, AWriteThatFailsMidwayNamesTheFileAndTheCause) {
  TempDir dir;
  const auto path = dir / "frame.png";
  std::vector<float> noise(std::size_t(256) * 256 * 3);
  std::uint32_t state = 12345;
  for (float& v : noise) v = static_cast<float>((state = state * 1664525u + 1013904223u) >> 8) / 16777216.0f;
  write_png(path, 256, 256, noise, ToneMapping::clamp);
  const auto full_bytes = std::filesystem::file_size(path);
  std::filesystem::remove(path);
  rlimit previous{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &previous), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = previous;
  // One byte short: the last bytes sit in the stream's buffer until the file
  // is closed, where the failure once lost its cause.
  small.rlim_cur = full_bytes - 1;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string error;
  try {
    write_png(path, 256, 256, noise, ToneMapping::clamp);
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &previous);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(error.find(path.string()), 0u) << error;
  EXPECT_NE(error.find("File too large"), std::string::npos) << "the cause, as strerror(EFBIG) says it: " << error;
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(dir / "frame.png.partial")) << "nothing half-written is left";
}

}  // namespace
}  // namespace zenith::image
