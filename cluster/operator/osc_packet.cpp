#include "cluster/operator/osc_packet.h"

#include <bit>
#include <cstring>

#include "core/strings.h"

namespace zenith::cluster {
namespace {

using core::cat;

constexpr std::size_t kMaxAddressBytes = 256;
constexpr std::size_t kMaxArguments = 32;
constexpr char kBundleTag[8] = {'#', 'b', 'u', 'n', 'd', 'l', 'e', '\0'};

/// Reads one OSC packet region; every read is checked against its end.
class Reader {
 public:
  Reader(std::span<const std::uint8_t> bytes, std::size_t base) : bytes_(bytes), base_(base) {}

  bool done() const { return at_ == bytes_.size(); }
  std::size_t remaining() const { return bytes_.size() - at_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw OscError(cat("OSC packet, byte ", base_ + at_, ": ", what));
  }

  /// A big-endian 32-bit word.
  std::uint32_t u32() {
    if (remaining() < 4) fail("4 bytes needed, the packet ends");
    const std::uint32_t v = std::uint32_t{bytes_[at_]} << 24 | std::uint32_t{bytes_[at_ + 1]} << 16 |
                            std::uint32_t{bytes_[at_ + 2]} << 8 | bytes_[at_ + 3];
    at_ += 4;
    return v;
  }
  /// A big-endian 64-bit word.
  std::uint64_t u64() {
    const std::uint64_t high = u32();
    return high << 32 | u32();
  }
  /// A string: bytes up to a NUL, padded with NULs to a multiple of 4.
  std::string string(std::size_t max_bytes) {
    const std::size_t start = at_;
    std::size_t end = start;
    while (end < bytes_.size() && bytes_[end] != 0) ++end;
    if (end == bytes_.size()) fail("a string without its terminating NUL");
    if (end - start > max_bytes) fail(cat("a string of ", end - start, " bytes; at most ", max_bytes));
    std::string text(reinterpret_cast<const char*>(bytes_.data() + start), end - start);
    const std::size_t padded = (end - start + 4) & ~std::size_t{3};
    if (bytes_.size() - start < padded) fail("a string's padding is cut off");
    for (std::size_t i = end; i < start + padded; ++i)
      if (bytes_[i] != 0) fail("a string's padding is not NUL");
    at_ = start + padded;
    return text;
  }
  /// A blob: its size (32 bits), the bytes, NULs up to a multiple of 4.
  std::vector<std::uint8_t> blob() {
    const std::uint32_t size = u32();
    if (size > remaining()) fail(cat("a blob of ", size, " bytes; ", remaining(), " are left"));
    std::vector<std::uint8_t> out(bytes_.begin() + static_cast<std::ptrdiff_t>(at_),
                                  bytes_.begin() + static_cast<std::ptrdiff_t>(at_ + size));
    const std::size_t padded = (std::size_t{size} + 3) & ~std::size_t{3};
    if (padded > remaining()) fail("a blob's padding is cut off");
    at_ += padded;
    return out;
  }
  /// The next `n` bytes.
  std::span<const std::uint8_t> take(std::size_t n) {
    if (n > remaining()) fail(cat(n, " bytes needed, ", remaining(), " are left"));
    const auto out = bytes_.subspan(at_, n);
    at_ += n;
    return out;
  }
  std::size_t offset() const { return base_ + at_; }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t base_;
  std::size_t at_ = 0;
};

/// Printable ASCII without space, '#' first or any of " #*,?[]{}" (OSC address pattern characters).
bool valid_address(const std::string& address) {
  if (address.empty() || address[0] != '/') return false;
  for (const char c : address)
    if (c < 0x21 || c > 0x7e || std::strchr("#*,?[]{}", c) != nullptr) return false;
  return true;
}

/// One message: address, type tags, arguments; nothing may follow.
OscMessage decode_message(Reader& r) {
  OscMessage message;
  message.address = r.string(kMaxAddressBytes);
  if (!valid_address(message.address))
    r.fail(cat("address \"", message.address,
               "\": must start with '/' and hold printable ASCII without spaces or "
               "pattern characters (# * , ? [ ] { })"));
  if (r.done()) return message;  // no type tag string: no arguments (OSC 1.0 tolerates old senders)
  const std::string tags = r.string(kMaxArguments + 1);
  if (tags.empty() || tags[0] != ',') r.fail(cat("type tags \"", tags, "\": must start with ','"));
  for (std::size_t i = 1; i < tags.size(); ++i) {
    switch (tags[i]) {
      case 'i': message.arguments.emplace_back(static_cast<std::int32_t>(r.u32())); break;
      case 'h': message.arguments.emplace_back(static_cast<std::int64_t>(r.u64())); break;
      case 'f': message.arguments.emplace_back(std::bit_cast<float>(r.u32())); break;
      case 'd': message.arguments.emplace_back(std::bit_cast<double>(r.u64())); break;
      case 's':
      case 'S': message.arguments.emplace_back(r.string(kMaxOscPacketBytes)); break;
      case 'b': message.arguments.emplace_back(OscBlob{r.blob()}); break;
      case 'T': message.arguments.emplace_back(true); break;
      case 'F': message.arguments.emplace_back(false); break;
      case 'N':
      case 'I': message.arguments.emplace_back(std::monostate{}); break;
      case 't': message.arguments.emplace_back(OscWord{'t', r.u64()}); break;
      case 'c':
      case 'r':
      case 'm': message.arguments.emplace_back(OscWord{tags[i], r.u32()}); break;
      default: r.fail(cat("type tag '", tags[i], "' is not supported (i f s S b h d t T F N I c r m are)"));
    }
  }
  if (!r.done()) r.fail(cat(r.remaining(), " bytes after the last argument"));
  return message;
}

/// A message or a bundle at byte `base` of the packet, `depth` bundles deep; its messages go to `out`.
void decode_element(std::span<const std::uint8_t> bytes, std::size_t base, int depth, std::vector<OscMessage>& out) {
  Reader r(bytes, base);
  if (bytes.size() % 4 != 0) r.fail(cat("an element of ", bytes.size(), " bytes: OSC sizes are multiples of 4"));
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kBundleTag, 8) == 0) {
    if (depth >= kMaxOscBundleDepth) r.fail(cat("bundles nested more than ", kMaxOscBundleDepth, " deep"));
    r.take(8);
    r.u64();  // the time tag: ignored, a cue applies when it arrives
    while (!r.done()) {
      const std::uint32_t size = r.u32();
      const std::size_t at = r.offset();
      decode_element(r.take(size), at, depth + 1, out);
    }
    return;
  }
  if (out.size() >= kMaxOscMessages) r.fail(cat("more than ", kMaxOscMessages, " messages in one packet"));
  out.push_back(decode_message(r));
}

/// Appends a big-endian 32-bit word.
void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}
/// Appends a big-endian 64-bit word.
void put_u64(std::vector<std::uint8_t>& out, std::uint64_t v) {
  put_u32(out, static_cast<std::uint32_t>(v >> 32));
  put_u32(out, static_cast<std::uint32_t>(v));
}
/// Appends an OSC string: the bytes, then 1 to 4 NULs up to a multiple of 4.
void put_string(std::vector<std::uint8_t>& out, const std::string& s) {
  out.insert(out.end(), s.begin(), s.end());
  do out.push_back(0);
  while (out.size() % 4 != 0);
}

}  // namespace

std::vector<OscMessage> decode_osc_packet(std::span<const std::uint8_t> packet) {
  if (packet.empty()) throw OscError("OSC packet, byte 0: empty");
  if (packet.size() > kMaxOscPacketBytes)
    throw OscError(cat("OSC packet of ", packet.size(), " bytes: at most ", kMaxOscPacketBytes));
  std::vector<OscMessage> messages;
  decode_element(packet, 0, 0, messages);
  return messages;
}

std::vector<std::uint8_t> encode_osc_message(const OscMessage& message) {
  if (message.address.empty() || message.address[0] != '/')
    throw std::invalid_argument(cat("OSC address \"", message.address, "\" must start with '/'"));
  std::vector<std::uint8_t> out;
  put_string(out, message.address);
  std::string tags = ",";
  std::vector<std::uint8_t> data;
  for (const OscArgument& a : message.arguments) {
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, std::monostate>)
            tags += 'N';
          else if constexpr (std::is_same_v<T, std::int32_t>)
            tags += 'i', put_u32(data, static_cast<std::uint32_t>(v));
          else if constexpr (std::is_same_v<T, std::int64_t>)
            tags += 'h', put_u64(data, static_cast<std::uint64_t>(v));
          else if constexpr (std::is_same_v<T, float>)
            tags += 'f', put_u32(data, std::bit_cast<std::uint32_t>(v));
          else if constexpr (std::is_same_v<T, double>)
            tags += 'd', put_u64(data, std::bit_cast<std::uint64_t>(v));
          else if constexpr (std::is_same_v<T, bool>)
            tags += v ? 'T' : 'F';
          else if constexpr (std::is_same_v<T, std::string>)
            tags += 's', put_string(data, v);
          else if constexpr (std::is_same_v<T, OscBlob>) {
            tags += 'b';
            put_u32(data, static_cast<std::uint32_t>(v.bytes.size()));
            data.insert(data.end(), v.bytes.begin(), v.bytes.end());
            while (data.size() % 4 != 0) data.push_back(0);
          } else {
            tags += v.tag;
            if (v.tag == 't')
              put_u64(data, v.value);
            else
              put_u32(data, static_cast<std::uint32_t>(v.value));
          }
        },
        a);
  }
  put_string(out, tags);
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

std::vector<std::uint8_t> encode_osc_bundle(const std::vector<std::vector<std::uint8_t>>& elements) {
  std::vector<std::uint8_t> out(std::begin(kBundleTag), std::end(kBundleTag));
  put_u64(out, 1);  // "immediately"
  for (const auto& e : elements) {
    put_u32(out, static_cast<std::uint32_t>(e.size()));
    out.insert(out.end(), e.begin(), e.end());
  }
  return out;
}

std::string describe(const OscArgument& argument) {
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>)
          return "nil";
        else if constexpr (std::is_same_v<T, bool>)
          return v ? "true" : "false";
        else if constexpr (std::is_same_v<T, std::string>)
          return cat("\"", v.size() > 64 ? v.substr(0, 61) + "..." : v, "\"");
        else if constexpr (std::is_same_v<T, OscBlob>)
          return cat("blob of ", v.bytes.size(), " bytes");
        else if constexpr (std::is_same_v<T, OscWord>)
          return cat("'", v.tag, "' ", v.value);
        else
          return cat(+v);
      },
      argument);
}

}  // namespace zenith::cluster
