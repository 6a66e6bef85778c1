#pragma once
// The cluster's datagrams (docs/protocol.md, "Datagrams"): the few small
// messages that must not wait behind a lost TCP segment — a scheduled frame
// (FrameSchedule + FrameState) and the clock exchange (ClockPing, ClockPong)
// — sent over UDP, authenticated with the session's key. A lost datagram is
// not resent: the master sends each scheduled frame again at every tick until
// it is due, so one loss costs nothing, and a clock sample is one of many.
//
//   offset  size  field
//        0     4  magic "ZNDG" (0x5A 0x4E 0x44 0x47)
//        4     4  node id (Welcome.node_id of the session), big-endian
//        8     …  one or more messages, each framed as on TCP (messages.h):
//                 header, version, CRCs and all
//    end−16    16  the first 16 bytes of HMAC-SHA256(datagram key, bytes 0 … end−17)
//
// The datagram key is the session's (handshake.h, datagram_key()): a
// datagram of another session, another node or another cluster, or one
// altered in flight, fails the tag and is dropped. Replays within a session
// are harmless: a frame already taken and an answered ping are ignored.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cluster/protocol/messages.h"

namespace zenith::cluster {

inline constexpr std::array<std::uint8_t, 4> kDatagramMagic = {'Z', 'N', 'D', 'G'};
inline constexpr std::size_t kDatagramTagBytes = 16;
inline constexpr std::size_t kDatagramHeaderBytes = 8;
/// What a datagram may hold at most: a FrameSchedule and a FrameState of the
/// largest size, framed, with the header and the tag (kept below 2 KiB, so
/// that a datagram is at most two Ethernet frames).
std::size_t max_datagram_bytes();

/// A datagram's node id, read before its tag is checked (to find the key).
/// Nothing when it is too short or its magic is wrong.
std::optional<std::uint32_t> datagram_node_id(std::span<const std::uint8_t> datagram);

/// `messages` (each of the types above: FrameSchedule, FrameState, ClockPing,
/// ClockPong) framed, behind the header, with the tag of `key`.
std::vector<std::uint8_t> seal_datagram(const Digest& key, std::uint32_t node_id, std::span<const Message> messages);

/// Why a datagram was refused (for a rate-limited log line).
struct DatagramRefusal {
  std::string what;
};
/// The messages of a datagram whose tag `key` confirms, in order; a
/// DatagramRefusal naming the field when the size, the magic, the tag, a
/// frame or a message type (not one of the four) is wrong.
struct OpenedDatagram {
  std::uint32_t node_id = 0;
  std::vector<Message> messages;
};
std::variant<OpenedDatagram, DatagramRefusal> open_datagram(const Digest& key, std::span<const std::uint8_t> datagram);

}  // namespace zenith::cluster
