#pragma once
// SHA-256 of bytes given piece by piece: fingerprints of structures hashed
// field by field without building a buffer (scene/frame_digest.h).
#include <cstddef>
#include <memory>

#include "core/sha256.h"

namespace zenith::core {

/// update() with each piece, then digest() once: equal to sha256() of the
/// pieces concatenated.
class Sha256Stream {
 public:
  Sha256Stream();  ///< Throws std::runtime_error if OpenSSL fails.
  ~Sha256Stream();
  Sha256Stream(const Sha256Stream&) = delete;
  Sha256Stream& operator=(const Sha256Stream&) = delete;

  void update(const void* data, std::size_t bytes);
  /// The digest of everything given; the stream is spent afterwards.
  Sha256Digest digest();

 private:
  struct Context;
  std::unique_ptr<Context> context_;
};

}  // namespace zenith::core
