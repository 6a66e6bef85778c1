#pragma once
// CRC-32C (Castagnoli): reflected polynomial 0x82F63B78, initial value and
// final XOR 0xFFFFFFFF, as in iSCSI (RFC 3720) and SCTP. Check value:
// crc32c("123456789") = 0xE3069283. Table-driven, slicing by 8 (no CPU
// intrinsics, so the result never depends on the machine).
#include <cstddef>
#include <cstdint>
#include <span>

namespace zenith::cluster {

/// CRC-32C of `data`.
std::uint32_t crc32c(std::span<const std::uint8_t> data);

/// Continues a CRC: crc32c_extend(crc32c(a), b) == crc32c(a ‖ b);
/// crc32c_extend(0, data) == crc32c(data).
std::uint32_t crc32c_extend(std::uint32_t crc, std::span<const std::uint8_t> data);

}  // namespace zenith::cluster
