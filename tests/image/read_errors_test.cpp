// read_image on files that are missing, not images, truncated or corrupted:
// always a std::runtime_error naming the file, never a crash.
#include <gtest/gtest.h>

#include <zlib.h>

#include <random>

#include "image/image_io.h"
#include "image/image_writer.h"
#include "tests/image/image_test_util.h"

namespace zenith::image {
namespace {

using testing::TempDir;

/// Expects read_image(path) to throw std::runtime_error whose message names the
/// file (and contains `reason` when given); returns the message.
std::string expect_read_error(const std::filesystem::path& path, const std::string& reason = "") {
  try {
    read_image(path);
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind(path.string() + ": ", 0), 0u) << m;
    if (!reason.empty()) {
      EXPECT_NE(m.find(reason), std::string::npos) << m;
    }
    return m;
  }
  ADD_FAILURE() << "no std::runtime_error for " << path;
  return {};
}

std::vector<unsigned char> valid_png(const TempDir& dir, int w = 12, int h = 10) {
  write_png(dir / "valid.png", w, h, testing::test_pattern(w, h), ToneMapping::exponential, {{"k", "v"}});
  return testing::read_bytes(dir / "valid.png");
}

std::vector<unsigned char> valid_exr(const TempDir& dir, ExrPixelType type = ExrPixelType::half, int w = 12,
                                     int h = 40) {
  write_exr(dir / "valid.exr", w, h, testing::test_pattern(w, h), type, {{"k", "v"}});
  return testing::read_bytes(dir / "valid.exr");
}

TEST(ReadImage, MissingFilesDirectoriesAndEmptyFiles) {
  TempDir dir;
  expect_read_error(dir / "missing.png", "no such file");
  expect_read_error(dir.path(), "is a directory");
  testing::write_bytes(dir / "empty.exr", {});
  expect_read_error(dir / "empty.exr", "empty file");
}

TEST(ReadImage, FilesThatAreNotImagesAreNamedByTheirMagicBytes) {
  TempDir dir;
  std::mt19937 rng(11);
  for (int i = 0; i < 20; ++i) {
    std::vector<unsigned char> bytes(std::size_t(1 + rng() % 3000));
    for (auto& b : bytes) b = static_cast<unsigned char>(rng());
    testing::write_bytes(dir / "random.png", bytes);
    expect_read_error(dir / "random.png", "not a PNG or OpenEXR file");
  }
  testing::write_bytes(dir / "text.exr", {'h', 'e', 'l', 'l', 'o', '\n'});
  expect_read_error(dir / "text.exr", "not a PNG or OpenEXR file");
}

TEST(ReadImage, RandomBytesAfterAValidMagicAreRejected) {
  TempDir dir;
  std::mt19937 rng(12);
  const std::vector<std::vector<unsigned char>> magics{{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'},
                                                       {0x76, 0x2f, 0x31, 0x01}};
  for (const auto& magic : magics)
    for (int i = 0; i < 50; ++i) {
      std::vector<unsigned char> bytes = magic;
      bytes.resize(magic.size() + rng() % 2000);
      for (std::size_t k = magic.size(); k < bytes.size(); ++k) bytes[k] = static_cast<unsigned char>(rng());
      testing::write_bytes(dir / "garbage", bytes);
      expect_read_error(dir / "garbage");
    }
}

TEST(ReadImage, EveryTruncationOfAPngIsAnError) {
  TempDir dir;
  const std::vector<unsigned char> png = valid_png(dir);
  ASSERT_NO_THROW(read_image(dir / "valid.png"));
  for (std::size_t n = 1; n < png.size(); ++n) {
    testing::write_bytes(dir / "cut.png", png, n);
    const std::string m = expect_read_error(dir / "cut.png");
    if (n >= 8) {
      EXPECT_NE(m.find("truncated"), std::string::npos) << n << ": " << m;
    }
  }
}

TEST(ReadImage, TruncatedExrFilesAreErrors) {
  TempDir dir;
  for (ExrPixelType type : {ExrPixelType::half, ExrPixelType::float32}) {
    const std::vector<unsigned char> exr = valid_exr(dir, type);
    ASSERT_NO_THROW(read_image(dir / "valid.exr"));
    // Half: every length through the header and offset table (~350 bytes), then
    // every 3rd; float: every 11th. (File I/O dominates the run time.)
    const bool dense = type == ExrPixelType::half;
    for (std::size_t n = 1; n < exr.size(); n += dense ? (n < 400 ? 1 : 3) : 11) {
      testing::write_bytes(dir / "cut.exr", exr, n);
      expect_read_error(dir / "cut.exr");
    }
  }
}

TEST(ReadImage, CorruptedFilesDecodeOrThrowButNeverCrash) {
  TempDir dir;
  std::mt19937 rng(13);
  int rejected = 0, total = 0;
  for (const auto& original :
       {valid_png(dir), valid_exr(dir, ExrPixelType::half), valid_exr(dir, ExrPixelType::float32)}) {
    for (int i = 0; i < 200; ++i) {
      std::vector<unsigned char> bytes = original;
      const int flips = 1 + int(rng() % 4);
      for (int k = 0; k < flips; ++k) bytes[rng() % bytes.size()] ^= static_cast<unsigned char>(1 + rng() % 255);
      testing::write_bytes(dir / "corrupt", bytes);
      ++total;
      try {
        const LinearImage image = read_image(dir / "corrupt");
        EXPECT_EQ(image.rgb.size(), std::size_t(image.width) * image.height * 3);
      } catch (const std::runtime_error& e) {
        ++rejected;
        EXPECT_EQ(std::string(e.what()).rfind((dir / "corrupt").string() + ": ", 0), 0u) << e.what();
      }
    }
  }
  EXPECT_GT(rejected, total / 4);  // most corruptions are caught (CRCs, zlib checksums, structure)
}

TEST(ReadImage, ImagesLargerThanTheLimitAreRejectedBeforeDecoding) {
  TempDir dir;
  // A PNG header claiming 40000 × 2 px (the rows are never reached).
  ASSERT_TRUE(testing::write_raw_png(dir / "wide.png", testing::black_raw_png(40000, 2, 1)));
  expect_read_error(dir / "wide.png", "larger than the 32768 px");
}

TEST(ReadImage, SizeFieldsThatPointPastTheFileAreRejectedBeforeAllocating) {
  TempDir dir;
  // EXR: the value size of the attribute "k" (written last) set to 2^31 − 1.
  std::vector<unsigned char> exr = valid_exr(dir);
  const std::string text(exr.begin(), exr.end());
  const std::size_t k = text.find(std::string("k\0string\0", 9));
  ASSERT_NE(k, std::string::npos);
  for (int i = 0; i < 4; ++i) exr[k + 9 + i] = i == 3 ? 0x7f : 0xff;
  testing::write_bytes(dir / "size.exr", exr);
  expect_read_error(dir / "size.exr", "attribute 'k' claims 2147483647 bytes");

  // EXR: the first chunk's data size set to 2^31 − 1.
  exr = valid_exr(dir);
  std::size_t p = 8;  // walk the attributes (name\0 type\0 int32 size, value) to the header's end
  while (exr[p] != 0) {
    p = text.find('\0', text.find('\0', p) + 1) + 1;
    p += 4 + (std::size_t(exr[p]) | std::size_t(exr[p + 1]) << 8);
  }
  const std::size_t table = p + 1;
  const std::size_t first_chunk = std::size_t(exr[table]) | std::size_t(exr[table + 1]) << 8;
  ASSERT_LT(first_chunk + 8, exr.size());
  for (int i = 0; i < 4; ++i) exr[first_chunk + 4 + i] = i == 3 ? 0x7f : 0xff;
  testing::write_bytes(dir / "chunk.exr", exr);
  expect_read_error(dir / "chunk.exr", "claims 2147483647 bytes");

  // PNG: a tEXt chunk claiming 2 GB (libpng allocates chunks whole; capped at 16 MiB).
  std::vector<unsigned char> png = valid_png(dir);
  const std::string png_text(png.begin(), png.end());
  const std::size_t t = png_text.find("tEXt");
  ASSERT_NE(t, std::string::npos);
  png[t - 4] = 0x7f;
  png[t - 3] = png[t - 2] = png[t - 1] = 0xff;
  testing::write_bytes(dir / "text.png", png);
  expect_read_error(dir / "text.png", "truncated");

  // PNG: a valid header claiming 30000 × 30000 px in a file of a few hundred bytes.
  ASSERT_TRUE(testing::write_raw_png(dir / "claim.png", testing::black_raw_png(3, 3, 3)));
  std::vector<unsigned char> claim = testing::read_bytes(dir / "claim.png");
  // IHDR data starts at byte 16: width, height (big endian); then fix the CRC.
  for (int i = 0; i < 2; ++i) {
    claim[16 + 4 * i + 2] = 0x75;  // 30000 = 0x7530
    claim[16 + 4 * i + 3] = 0x30;
  }
  const uLong crc = crc32(0, claim.data() + 12, 17);
  for (int i = 0; i < 4; ++i) claim[29 + i] = static_cast<unsigned char>(crc >> (24 - 8 * i));
  testing::write_bytes(dir / "claim.png", claim);
  expect_read_error(dir / "claim.png", "cannot hold a 30000x30000 image");
}

}  // namespace
}  // namespace zenith::image
