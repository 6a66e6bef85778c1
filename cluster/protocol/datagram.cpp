#include "cluster/protocol/datagram.h"

#include <openssl/crypto.h>

#include <algorithm>

#include "cluster/protocol/frame_decoder.h"
#include "cluster/protocol/handshake.h"

namespace zenith::cluster {
namespace {

bool allowed_in_datagram(MessageType type) {
  return type == MessageType::frame_schedule || type == MessageType::frame_state || type == MessageType::clock_ping ||
         type == MessageType::clock_pong;
}

std::array<std::uint8_t, kDatagramTagBytes> tag(const Digest& key, std::span<const std::uint8_t> covered) {
  const Digest mac = hmac_sha256(key, covered);
  std::array<std::uint8_t, kDatagramTagBytes> out{};
  std::copy_n(mac.begin(), kDatagramTagBytes, out.begin());
  return out;
}

}  // namespace

std::size_t max_datagram_bytes() {
  return kDatagramHeaderBytes + 2 * kHeaderBytes +
         *max_payload_bytes(static_cast<std::uint16_t>(MessageType::frame_schedule)) +
         *max_payload_bytes(static_cast<std::uint16_t>(MessageType::frame_state)) + kDatagramTagBytes;
}

std::optional<std::uint32_t> datagram_node_id(std::span<const std::uint8_t> d) {
  if (d.size() < kDatagramHeaderBytes + kDatagramTagBytes ||
      !std::equal(kDatagramMagic.begin(), kDatagramMagic.end(), d.begin()))
    return std::nullopt;
  return std::uint32_t{d[4]} << 24 | std::uint32_t{d[5]} << 16 | std::uint32_t{d[6]} << 8 | d[7];
}

std::vector<std::uint8_t> seal_datagram(const Digest& key, std::uint32_t node_id, std::span<const Message> messages) {
  std::vector<std::uint8_t> out(kDatagramMagic.begin(), kDatagramMagic.end());
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(node_id >> shift));
  for (const Message& m : messages) {
    if (!allowed_in_datagram(message_type(m)))
      throw std::invalid_argument(std::string("cannot send ") + to_string(message_type(m)) + " in a datagram");
    const std::vector<std::uint8_t> framed = encode(m);
    out.insert(out.end(), framed.begin(), framed.end());
  }
  const auto t = tag(key, out);
  out.insert(out.end(), t.begin(), t.end());
  if (out.size() > max_datagram_bytes()) throw std::length_error("datagram above its maximum size");
  return out;
}

std::variant<OpenedDatagram, DatagramRefusal> open_datagram(const Digest& key, std::span<const std::uint8_t> d) {
  const std::optional<std::uint32_t> id = datagram_node_id(d);
  if (!id) return DatagramRefusal{"not a zenith datagram (too short, or no \"ZNDG\" magic)"};
  if (d.size() > max_datagram_bytes())
    return DatagramRefusal{"datagram of " + std::to_string(d.size()) + " bytes, at most " +
                           std::to_string(max_datagram_bytes())};
  const std::span<const std::uint8_t> covered = d.first(d.size() - kDatagramTagBytes);
  const auto expected = tag(key, covered);
  if (CRYPTO_memcmp(expected.data(), d.data() + covered.size(), kDatagramTagBytes) != 0)
    return DatagramRefusal{"datagram tag does not match (another session's or cluster's key, or altered)"};
  OpenedDatagram opened{*id, {}};
  FrameDecoder decoder;
  decoder.feed(covered.subspan(kDatagramHeaderBytes));
  try {
    while (std::optional<Message> m = decoder.next()) {
      if (!allowed_in_datagram(message_type(*m)))
        return DatagramRefusal{std::string(to_string(message_type(*m))) + " is not sent in a datagram"};
      opened.messages.push_back(std::move(*m));
    }
  } catch (const ProtocolError& e) {
    return DatagramRefusal{std::string("datagram message: ") + e.what()};
  }
  if (decoder.buffered_bytes() != 0) return DatagramRefusal{"datagram ends inside a message"};
  if (opened.messages.empty()) return DatagramRefusal{"datagram holds no message"};
  return opened;
}

}  // namespace zenith::cluster
