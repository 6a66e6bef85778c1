#include "cluster/protocol/crc32c.h"

#include <gtest/gtest.h>

#include <random>
#include <string_view>
#include <vector>

namespace zenith::cluster {
namespace {

std::span<const std::uint8_t> as_bytes(std::string_view s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

// Bit-at-a-time definition, independent of the tables.
std::uint32_t crc32c_bitwise(std::span<const std::uint8_t> data) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::uint8_t b : data) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? (c >> 1) ^ 0x82F63B78u : c >> 1;
  }
  return ~c;
}

TEST(Crc32c, CheckValueOf123456789) { EXPECT_EQ(crc32c(as_bytes("123456789")), 0xE3069283u); }

TEST(Crc32c, ThirtyTwoZeroBytes) {
  const std::vector<std::uint8_t> zeros(32, 0);
  EXPECT_EQ(crc32c(zeros), 0x8A9136AAu);
}

TEST(Crc32c, Rfc3720Vectors) {
  const std::vector<std::uint8_t> ones(32, 0xFF);
  EXPECT_EQ(crc32c(ones), 0x62A8AB43u);
  std::vector<std::uint8_t> ascending(32);
  for (int i = 0; i < 32; ++i) ascending[i] = static_cast<std::uint8_t>(i);
  EXPECT_EQ(crc32c(ascending), 0x46DD794Eu);
  EXPECT_EQ(crc32c({}), 0u);
}

TEST(Crc32c, SlicedTablesMatchTheBitwiseDefinitionAtEveryLengthAndAlignment) {
  std::mt19937 rng(7);
  std::vector<std::uint8_t> data(300);
  for (auto& b : data) b = static_cast<std::uint8_t>(rng());
  for (std::size_t offset = 0; offset < 8; ++offset)
    for (std::size_t n = 0; n + offset <= data.size(); n += 13) {
      std::span<const std::uint8_t> s(data.data() + offset, n);
      ASSERT_EQ(crc32c(s), crc32c_bitwise(s)) << "offset " << offset << " length " << n;
    }
}

TEST(Crc32c, ExtendEqualsCrcOfConcatenation) {
  const std::string_view a = "zenith cluster ", b = "frame 42";
  const std::string ab = std::string(a) + std::string(b);
  EXPECT_EQ(crc32c_extend(crc32c(as_bytes(a)), as_bytes(b)), crc32c(as_bytes(ab)));
}

}  // namespace
}  // namespace zenith::cluster
