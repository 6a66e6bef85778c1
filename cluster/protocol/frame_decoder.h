#pragma once
// Incremental frame decoder: bytes go in as the socket delivers them, whole
// messages come out.
//
//   FrameDecoder decoder;
//   decoder.feed(received);                  // any number of bytes, any split
//   while (auto message = decoder.next()) handle(*message);
//
// Each header is validated the moment its 20 bytes are in: a bad magic, an
// unsupported version, an unknown type or a length above the type's maximum is
// reported without waiting for (or buffering) the payload. The partial frame
// buffer never holds more than kHeaderBytes + max_payload_bytes(type) bytes.
// Complete frames are decoded inside feed() and queued for next(), so what is
// queued is bounded by what one feed() handed over: feed socket reads of a
// bounded size and drain next() after each.
//
// next() returns the queued messages in order, then throws the ProtocolError
// that stopped decoding, if any. After an error the decoder is poisoned: it
// ignores further bytes and next() keeps throwing the same error. The caller
// logs it and closes the connection: there is no resynchronisation.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cluster/protocol/messages.h"
#include "cluster/protocol/protocol_error.h"

namespace zenith::cluster {

class FrameDecoder {
 public:
  /// Appends bytes received from the peer and decodes every frame they complete.
  /// Never throws ProtocolError (errors are reported by next()); may throw std::bad_alloc.
  void feed(std::span<const std::uint8_t> bytes);

  /// The next decoded message, or nullopt when no complete frame is buffered.
  /// Throws ProtocolError once the queued messages before the error are taken.
  std::optional<Message> next();

  /// Bytes of the frame being assembled (header and payload so far).
  std::size_t buffered_bytes() const { return frame_.size(); }
  /// Upper bound of buffered_bytes(): kHeaderBytes + the largest maximum payload.
  static std::size_t max_buffered_bytes();
  /// Decoded messages waiting for next().
  std::size_t queued_messages() const { return ready_.size(); }
  /// True once a ProtocolError occurred.
  bool poisoned() const { return error_.has_value(); }

  /// A limit on every payload from now on, below the types' own maxima:
  /// `max_bytes`, named `why` in the error ("before the handshake"); a
  /// header above it is **oversized** before any payload is buffered. The
  /// master sets kMaxHandshakePayloadBytes on a connection until the peer
  /// proved the secret, so an unauthenticated peer never makes it hold more
  /// than a handshake message (docs/protocol.md, "Framing").
  void limit_payload(std::uint32_t max_bytes, std::string why);
  /// Lifts the limit: each type's maximum again.
  void lift_payload_limit() { limit_.reset(); }

 private:
  void complete_frame();

  std::vector<std::uint8_t> frame_;    ///< header + payload bytes of the current frame
  std::optional<FrameHeader> header_;  ///< set once the current header validated
  std::deque<Message> ready_;
  std::optional<ProtocolError> error_;
  struct Limit {
    std::uint32_t max_bytes;
    std::string why;
  };
  std::optional<Limit> limit_;
};

/// The largest payload a peer may send before the handshake completes: the
/// largest of Hello, Authenticate and Goodbye (Goodbye's 1026 bytes).
std::uint32_t max_handshake_payload_bytes();

}  // namespace zenith::cluster
