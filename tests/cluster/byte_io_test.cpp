#include "cluster/protocol/byte_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace zenith::cluster {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(ByteIo, WritesBigEndianRegardlessOfTheHost) {
  Bytes out;
  ByteWriter w(out);
  w.u8(0xAB);
  w.u16(0x1234);
  w.u32(0x89ABCDEFu);
  w.u64(0x0102030405060708ull);
  w.i64(-2);
  w.f64(1.0);
  w.f64(-0.0);
  const Bytes expected = {0xAB, 0x12, 0x34, 0x89, 0xAB, 0xCD, 0xEF, 1,    2,    3,    4,    5,    6,
                          7,    8,    0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFE, 0x3F, 0xF0, 0,
                          0,    0,    0,    0,    0,    0x80, 0,    0,    0,    0,    0,    0,    0};
  EXPECT_EQ(out, expected);
}

TEST(ByteIo, ReadsWhatItWroteIncludingSpecialDoubles) {
  Bytes out;
  ByteWriter w(out);
  const double values[] = {0.0, -0.0, 1e-310, 6371000.5, -1e300, std::numeric_limits<double>::infinity()};
  for (double v : values) w.f64(v);
  w.i64(std::numeric_limits<std::int64_t>::min());
  w.string("Zürich", 64, "name");
  ByteReader r(out);
  for (double v : values) {
    const double got = r.f64("value");
    EXPECT_EQ(std::signbit(got), std::signbit(v));
    EXPECT_EQ(got, v);
  }
  EXPECT_EQ(r.i64("i"), std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(r.string(64, "name"), "Zürich");
  EXPECT_EQ(r.remaining(), 0u);
  EXPECT_NO_THROW(r.expect_end("test"));
}

TEST(ByteIo, StringIsU16LengthThenUtf8Bytes) {
  Bytes out;
  ByteWriter w(out);
  w.string("é", 10, "s");
  EXPECT_EQ(out, (Bytes{0x00, 0x02, 0xC3, 0xA9}));
  EXPECT_THROW(w.string(std::string(11, 'x'), 10, "s"), std::length_error);
  EXPECT_THROW(w.string("\xC3", 10, "s"), std::invalid_argument);
}

TEST(ByteIo, TruncatedReadNamesTheFieldAndNeverReadsPastTheEnd) {
  const Bytes data = {1, 2, 3};
  ByteReader r(data);
  EXPECT_EQ(r.u16("first"), 0x0102);
  try {
    r.u32("Welcome.node_id");
    FAIL() << "no exception";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), ProtocolErrorCode::malformed_payload);
    EXPECT_NE(std::string(e.what()).find("Welcome.node_id: truncated"), std::string::npos) << e.what();
  }
  EXPECT_EQ(r.offset(), 2u);  // a failed read consumes nothing
  EXPECT_EQ(r.u8("last"), 3);
}

TEST(ByteIo, StringLengthAboveTheLimitIsRefusedBeforeTheBytes) {
  const Bytes data = {0xFF, 0xFF};  // claims 65535 bytes, none present
  ByteReader r(data);
  try {
    r.string(64, "Hello.node_name");
    FAIL() << "no exception";
  } catch (const ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("Hello.node_name: length 65535 exceeds the limit of 64"), std::string::npos)
        << e.what();
  }
}

TEST(ByteIo, ReaderRefusesInvalidUtf8) {
  const Bytes data = {0x00, 0x02, 0xC0, 0x80};  // overlong NUL
  ByteReader r(data);
  EXPECT_THROW(r.string(64, "name"), ProtocolError);
}

TEST(ByteIo, Utf8Validation) {
  EXPECT_TRUE(is_valid_utf8(""));
  EXPECT_TRUE(is_valid_utf8("plain ascii"));
  EXPECT_TRUE(is_valid_utf8("\xE2\x82\xAC \xF0\x9F\x8C\x8D"));  // € 🌍
  EXPECT_FALSE(is_valid_utf8(std::string_view("a\0b", 3)));
  EXPECT_FALSE(is_valid_utf8("\x80"));
  EXPECT_FALSE(is_valid_utf8("\xC3"));              // truncated
  EXPECT_FALSE(is_valid_utf8("\xE0\x80\x80"));      // overlong
  EXPECT_FALSE(is_valid_utf8("\xED\xA0\x80"));      // surrogate
  EXPECT_FALSE(is_valid_utf8("\xF4\x90\x80\x80"));  // above U+10FFFF
  EXPECT_FALSE(is_valid_utf8("\xFF"));
}

}  // namespace
}  // namespace zenith::cluster
