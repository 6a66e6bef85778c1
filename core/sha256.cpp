#include "core/sha256.h"

#include <openssl/evp.h>

#include <stdexcept>

namespace zenith::core {

Sha256Digest sha256(const void* data, std::size_t bytes) {
  Sha256Digest out{};
  unsigned int length = 0;
  if (EVP_Digest(data, bytes, out.data(), &length, EVP_sha256(), nullptr) != 1 || length != out.size())
    throw std::runtime_error("SHA-256 failed (OpenSSL EVP_Digest)");
  return out;
}

std::string sha256_hex(const void* data, std::size_t bytes) { return to_hex(sha256(data, bytes)); }

std::string to_hex(const Sha256Digest& digest) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(2 * digest.size());
  for (const std::uint8_t b : digest) {
    out += kHex[b >> 4];
    out += kHex[b & 15];
  }
  return out;
}

Sha256Digest digest_from_hex(std::string_view hex) {
  if (hex.size() != 64)
    throw std::invalid_argument("digest: expected 64 hex digits, got " + std::to_string(hex.size()) + " characters");
  const auto nibble = [&](char c) -> std::uint8_t {
    if (c >= '0' && c <= '9') return static_cast<std::uint8_t>(c - '0');
    if (c >= 'a' && c <= 'f') return static_cast<std::uint8_t>(c - 'a' + 10);
    if (c >= 'A' && c <= 'F') return static_cast<std::uint8_t>(c - 'A' + 10);
    throw std::invalid_argument("digest: '" + std::string(hex) + "' is not hexadecimal");
  };
  Sha256Digest d{};
  for (std::size_t i = 0; i < d.size(); ++i)
    d[i] = static_cast<std::uint8_t>(nibble(hex[2 * i]) << 4 | nibble(hex[2 * i + 1]));
  return d;
}

}  // namespace zenith::core
