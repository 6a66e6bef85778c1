#pragma once
// A minimal Open Sound Control 1.0 decoder (docs/operator.md, "OSC"): the
// messages of one UDP datagram, as show-control desks send them. Our own
// rather than liblo: the operator needs a dozen addresses with one number
// each, the decoder is about 130 lines with bounds checked at every
// read, it is fuzzed (tests/cluster/osc_test.cpp), and the master keeps its
// single event loop (liblo's server brings its own thread).
//
// Supported: messages and bundles (nested, their time tags ignored: a cue
// applies when it arrives), argument types i f s S b h d t T F N I c r m.
// Arrays ([ ]) are refused. Every error is an OscError naming the byte offset.
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace zenith::cluster {

/// The largest packet decoded (a UDP datagram on an ordinary network is smaller).
inline constexpr std::size_t kMaxOscPacketBytes = 64 * 1024;
/// The most messages a packet (with its bundles) may hold, and bundles may nest.
inline constexpr std::size_t kMaxOscMessages = 64;
inline constexpr int kMaxOscBundleDepth = 8;

class OscError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An OSC argument. Numbers keep their wire type (i, h: integers; f, d:
/// reals); T and F are booleans; s and S strings; b blobs; N and I carry no
/// value (std::monostate); t time tags, c, r and m are 32 or 64 bit words.
struct OscBlob {
  std::vector<std::uint8_t> bytes;
  bool operator==(const OscBlob&) const = default;
};
struct OscWord {
  char tag = 0;  ///< 't', 'c', 'r' or 'm'
  std::uint64_t value = 0;
  bool operator==(const OscWord&) const = default;
};
using OscArgument =
    std::variant<std::monostate, std::int32_t, std::int64_t, float, double, bool, std::string, OscBlob, OscWord>;

struct OscMessage {
  std::string address;  ///< starts with '/', printable ASCII without spaces
  std::vector<OscArgument> arguments;
  bool operator==(const OscMessage&) const = default;
};

/// Every message of one packet, bundles flattened in order. Throws OscError.
std::vector<OscMessage> decode_osc_packet(std::span<const std::uint8_t> packet);

/// Encodes a message (for tests and `zenith`'s own senders): address, type
/// tags, arguments, each padded to 4 bytes. Throws std::invalid_argument for an
/// address that does not start with '/'.
std::vector<std::uint8_t> encode_osc_message(const OscMessage& message);

/// A bundle of encoded elements (messages or bundles), time tag "immediately".
std::vector<std::uint8_t> encode_osc_bundle(const std::vector<std::vector<std::uint8_t>>& elements);

/// "1.5", "\"pickering\"", "true", "blob of 3 bytes": for log lines.
std::string describe(const OscArgument& argument);

}  // namespace zenith::cluster
