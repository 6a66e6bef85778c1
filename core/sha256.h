#pragma once
// SHA-256 (FIPS 180-4) of a byte range, through OpenSSL's EVP interface: the
// table versions and cache checksums, table transfers, show manifests.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace zenith::core {

using Sha256Digest = std::array<std::uint8_t, 32>;

/// SHA-256 of `bytes` bytes at `data`. Throws std::runtime_error if OpenSSL fails.
Sha256Digest sha256(const void* data, std::size_t bytes);
/// The same as 64 lowercase hex digits.
std::string sha256_hex(const void* data, std::size_t bytes);

/// A digest as 64 lowercase hex digits.
std::string to_hex(const Sha256Digest& digest);
/// Parses 64 hex digits (either case); throws std::invalid_argument otherwise.
Sha256Digest digest_from_hex(std::string_view hex);

}  // namespace zenith::core
