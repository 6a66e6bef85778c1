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

std::string sha256_hex(const void* data, std::size_t bytes) {
  static constexpr char kHex[] = "0123456789abcdef";
  const Sha256Digest digest = sha256(data, bytes);
  std::string out;
  out.reserve(2 * digest.size());
  for (const std::uint8_t b : digest) {
    out += kHex[b >> 4];
    out += kHex[b & 15];
  }
  return out;
}

}  // namespace zenith::core
