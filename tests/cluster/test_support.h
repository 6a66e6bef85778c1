#pragma once
// Helpers shared by the cluster tests: crafting frames byte by byte, digests.
#include <cstdint>
#include <span>
#include <vector>

#include "cluster/protocol/crc32c.h"
#include "cluster/protocol/messages.h"

namespace zenith::cluster::test {

/// A digest told apart by its first byte (table hashes in the master's bookkeeping tests).
inline Digest digest(std::uint8_t first) {
  Digest d{};
  d[0] = first;
  return d;
}

inline void put_be16(std::vector<std::uint8_t>& b, std::size_t at, std::uint16_t v) {
  b[at] = static_cast<std::uint8_t>(v >> 8);
  b[at + 1] = static_cast<std::uint8_t>(v);
}
inline void put_be32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (24 - 8 * i));
}
/// A frame with an arbitrary type and payload, correct magic, version, length and CRC.
inline std::vector<std::uint8_t> raw_frame(std::uint16_t type, const std::vector<std::uint8_t>& payload) {
  std::vector<std::uint8_t> f(kHeaderBytes, 0);
  f[0] = 'Z';
  f[1] = 'N';
  f[2] = 'T';
  f[3] = 'H';
  put_be16(f, 4, kProtocolVersion);
  put_be16(f, 6, type);
  put_be32(f, 8, static_cast<std::uint32_t>(payload.size()));
  put_be32(f, 12, crc32c(payload));
  put_be32(f, 16, crc32c(std::span<const std::uint8_t>(f).first(16)));
  f.insert(f.end(), payload.begin(), payload.end());
  return f;
}
/// Rewrites the payload CRC to match the bytes after the header (whatever the
/// length field says), then the header CRC to match header bytes 0..15.
inline void fix_crc(std::vector<std::uint8_t>& frame) {
  put_be32(frame, 12, crc32c(std::span<const std::uint8_t>(frame).subspan(kHeaderBytes)));
  put_be32(frame, 16, crc32c(std::span<const std::uint8_t>(frame).first(16)));
}
/// Rewrites only the header CRC.
inline void fix_header_crc(std::vector<std::uint8_t>& frame) {
  put_be32(frame, 16, crc32c(std::span<const std::uint8_t>(frame).first(16)));
}

}  // namespace zenith::cluster::test
