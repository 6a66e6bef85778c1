#include "core/sha256_stream.h"

#include <openssl/evp.h>

#include <stdexcept>

namespace zenith::core {

struct Sha256Stream::Context {
  EVP_MD_CTX* md = nullptr;
};

Sha256Stream::Sha256Stream() : context_(std::make_unique<Context>()) {
  context_->md = EVP_MD_CTX_new();
  if (context_->md == nullptr || EVP_DigestInit_ex(context_->md, EVP_sha256(), nullptr) != 1) {
    EVP_MD_CTX_free(context_->md);
    throw std::runtime_error("SHA-256 failed (OpenSSL EVP_DigestInit_ex)");
  }
}

Sha256Stream::~Sha256Stream() { EVP_MD_CTX_free(context_->md); }

void Sha256Stream::update(const void* data, std::size_t bytes) {
  if (EVP_DigestUpdate(context_->md, data, bytes) != 1)
    throw std::runtime_error("SHA-256 failed (OpenSSL EVP_DigestUpdate)");
}

Sha256Digest Sha256Stream::digest() {
  Sha256Digest out{};
  unsigned int length = 0;
  if (EVP_DigestFinal_ex(context_->md, out.data(), &length) != 1 || length != out.size())
    throw std::runtime_error("SHA-256 failed (OpenSSL EVP_DigestFinal_ex)");
  return out;
}

}  // namespace zenith::core
