#pragma once
// The one error type of the wire protocol. Every way a peer's bytes can be
// wrong maps to one code; the message names the field at fault, so the log
// line that closes the connection says what was wrong and where.
#include <stdexcept>
#include <string>

namespace zenith::cluster {

/// Why a frame was refused. Any of these closes the connection.
enum class ProtocolErrorCode {
  bad_magic,            ///< the first 4 bytes of a header are not "ZNTH"
  unsupported_version,  ///< header (or Hello) protocol version other than kProtocolVersion
  unknown_type,         ///< message type not defined by this protocol version
  oversized,            ///< payload length above the type's maximum (checked from the header alone)
  crc_mismatch,         ///< CRC-32C of the payload differs from the header's
  malformed_payload,    ///< a field is truncated, too long, out of range or not valid UTF-8
  trailing_bytes,       ///< bytes left in the payload after its last field
};

/// "bad_magic", "unsupported_version", ...
constexpr const char* to_string(ProtocolErrorCode code) {
  switch (code) {
    case ProtocolErrorCode::bad_magic: return "bad_magic";
    case ProtocolErrorCode::unsupported_version: return "unsupported_version";
    case ProtocolErrorCode::unknown_type: return "unknown_type";
    case ProtocolErrorCode::oversized: return "oversized";
    case ProtocolErrorCode::crc_mismatch: return "crc_mismatch";
    case ProtocolErrorCode::malformed_payload: return "malformed_payload";
    case ProtocolErrorCode::trailing_bytes: return "trailing_bytes";
  }
  return "unknown";
}

/// A peer sent bytes that are not a valid frame. what() is
/// "<code>: <detail naming the field>".
class ProtocolError : public std::runtime_error {
 public:
  ProtocolError(ProtocolErrorCode code, const std::string& detail)
      : std::runtime_error(std::string(to_string(code)) + ": " + detail), code_(code) {}
  ProtocolErrorCode code() const noexcept { return code_; }

 private:
  ProtocolErrorCode code_;
};

}  // namespace zenith::cluster
