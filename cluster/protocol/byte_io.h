#pragma once
// Explicit big-endian (network byte order) serialization.
//
// ByteWriter appends to a byte vector; ByteReader reads from a span and never
// reads past its end. Integers are written most significant byte first, f64 as
// the IEEE-754 binary64 bit pattern in the same order, strings as a u16 byte
// count followed by that many UTF-8 bytes (no terminator), blobs as raw bytes
// whose length the caller writes (or knows). Nothing here depends on the host's
// byte order or on struct layout.
//
// Every read names its field: a truncated or invalid field throws
// ProtocolError(malformed_payload) with that name, the offset and the sizes.
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cluster/protocol/protocol_error.h"

namespace zenith::cluster {

/// True when `bytes` is well-formed UTF-8 (no overlong forms, no surrogates,
/// nothing above U+10FFFF). NUL is allowed by UTF-8 but refused here: strings
/// on the wire are names and log text.
inline bool is_valid_utf8(std::string_view bytes) {
  std::size_t i = 0;
  const std::size_t n = bytes.size();
  while (i < n) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    if (c == 0) return false;
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t extra = 0;
    std::uint32_t code = 0;
    if ((c & 0xE0) == 0xC0) {
      extra = 1;
      code = c & 0x1Fu;
    } else if ((c & 0xF0) == 0xE0) {
      extra = 2;
      code = c & 0x0Fu;
    } else if ((c & 0xF8) == 0xF0) {
      extra = 3;
      code = c & 0x07u;
    } else {
      return false;  // continuation byte in lead position, or 0xF8..0xFF
    }
    if (n - i <= extra) return false;
    for (std::size_t k = 1; k <= extra; ++k) {
      const auto cc = static_cast<unsigned char>(bytes[i + k]);
      if ((cc & 0xC0) != 0x80) return false;
      code = (code << 6) | (cc & 0x3Fu);
    }
    static constexpr std::uint32_t kMinimum[4] = {0, 0x80, 0x800, 0x10000};
    if (code < kMinimum[extra] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return false;
    i += extra + 1;
  }
  return true;
}

/// Appends big-endian fields to a byte vector.
class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}

  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) { put_be(v, 2); }
  void u32(std::uint32_t v) { put_be(v, 4); }
  void u64(std::uint64_t v) { put_be(v, 8); }
  void i64(std::int64_t v) { put_be(static_cast<std::uint64_t>(v), 8); }
  /// The IEEE-754 binary64 bit pattern, big-endian (NaN payloads preserved).
  void f64(double v) { put_be(std::bit_cast<std::uint64_t>(v), 8); }
  void bytes(std::span<const std::uint8_t> data) { out_.insert(out_.end(), data.begin(), data.end()); }
  /// u16 byte count, then the bytes. Throws std::length_error naming `field`
  /// when longer than `max_bytes` (or 65535), std::invalid_argument when not
  /// valid UTF-8: a writer never produces what a reader would refuse.
  void string(std::string_view s, std::size_t max_bytes, const char* field) { text(s, max_bytes, 2, field); }
  /// u32 byte count, then the bytes: for long texts (JSON documents). Same
  /// errors as string().
  void long_string(std::string_view s, std::size_t max_bytes, const char* field) { text(s, max_bytes, 4, field); }

 private:
  void put_be(std::uint64_t v, int count) {
    for (int i = count - 1; i >= 0; --i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  /// A `length_bytes`-byte (2 or 4) count, then the UTF-8 bytes.
  void text(std::string_view s, std::size_t max_bytes, int length_bytes, const char* field) {
    const std::uint64_t representable = (std::uint64_t{1} << (8 * length_bytes)) - 1;
    if (s.size() > max_bytes || s.size() > representable)
      throw std::length_error(std::string(field) + ": " + std::to_string(s.size()) + " bytes, at most " +
                              std::to_string(max_bytes) + " allowed");
    if (!is_valid_utf8(s)) throw std::invalid_argument(std::string(field) + ": not valid UTF-8 (or contains NUL)");
    put_be(s.size(), length_bytes);
    out_.insert(out_.end(), s.begin(), s.end());
  }
  std::vector<std::uint8_t>& out_;
};

/// Reads big-endian fields from a span; never past its end.
class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> data) : data_(data) {}

  std::uint8_t u8(const char* field) { return static_cast<std::uint8_t>(get_be(1, field)); }
  std::uint16_t u16(const char* field) { return static_cast<std::uint16_t>(get_be(2, field)); }
  std::uint32_t u32(const char* field) { return static_cast<std::uint32_t>(get_be(4, field)); }
  std::uint64_t u64(const char* field) { return get_be(8, field); }
  std::int64_t i64(const char* field) { return static_cast<std::int64_t>(get_be(8, field)); }
  double f64(const char* field) { return std::bit_cast<double>(get_be(8, field)); }

  /// The next `count` bytes (a view into the input).
  std::span<const std::uint8_t> bytes(std::size_t count, const char* field) {
    require(count, field);
    auto view = data_.subspan(offset_, count);
    offset_ += count;
    return view;
  }
  template <std::size_t N>
  std::array<std::uint8_t, N> array(const char* field) {
    std::array<std::uint8_t, N> out{};
    auto view = bytes(N, field);
    std::memcpy(out.data(), view.data(), N);
    return out;
  }
  /// A u16-length-prefixed UTF-8 string of at most `max_bytes` bytes. The
  /// length is checked before the bytes are copied.
  std::string string(std::size_t max_bytes, const char* field) { return text(u16(field), max_bytes, field); }
  /// A u32-length-prefixed UTF-8 string (long_string()), length checked first.
  std::string long_string(std::size_t max_bytes, const char* field) { return text(u32(field), max_bytes, field); }

  std::size_t offset() const { return offset_; }
  std::size_t remaining() const { return data_.size() - offset_; }

  /// Throws ProtocolError(trailing_bytes) unless every byte was read.
  void expect_end(const char* what) const {
    if (remaining() != 0)
      throw ProtocolError(ProtocolErrorCode::trailing_bytes, std::string(what) + ": " + std::to_string(remaining()) +
                                                                 " trailing byte(s) after the last field");
  }
  /// Throws ProtocolError(malformed_payload) with `detail`.
  [[noreturn]] static void fail(const std::string& detail) {
    throw ProtocolError(ProtocolErrorCode::malformed_payload, detail);
  }

 private:
  /// `length` bytes of UTF-8 after a length field, checked against `max_bytes` before they are copied.
  std::string text(std::size_t length, std::size_t max_bytes, const char* field) {
    if (length > max_bytes)
      fail(std::string(field) + ": length " + std::to_string(length) + " exceeds the limit of " +
           std::to_string(max_bytes) + " bytes");
    auto view = bytes(length, field);
    std::string s(reinterpret_cast<const char*>(view.data()), view.size());
    if (!is_valid_utf8(s)) fail(std::string(field) + ": not valid UTF-8 (or contains NUL)");
    return s;
  }
  void require(std::size_t count, const char* field) const {
    if (count > remaining())
      fail(std::string(field) + ": truncated (needs " + std::to_string(count) + " byte(s) at offset " +
           std::to_string(offset_) + ", " + std::to_string(remaining()) + " left)");
  }
  std::uint64_t get_be(int count, const char* field) {
    require(static_cast<std::size_t>(count), field);
    std::uint64_t v = 0;
    for (int i = 0; i < count; ++i) v = (v << 8) | data_[offset_ + static_cast<std::size_t>(i)];
    offset_ += static_cast<std::size_t>(count);
    return v;
  }

  std::span<const std::uint8_t> data_;
  std::size_t offset_ = 0;
};

}  // namespace zenith::cluster
