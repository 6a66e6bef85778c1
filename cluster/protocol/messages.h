#pragma once
// The cluster's messages and their wire encoding (docs/protocol.md).
//
// A frame is a 20-byte header followed by a payload, all big-endian:
//
//   offset  size  field
//        0     4  magic "ZNTH" (0x5A 0x4E 0x54 0x48)
//        4     2  protocol version (kProtocolVersion)
//        6     2  message type (MessageType)
//        8     4  payload length in bytes (≤ max_payload_bytes(type))
//       12     4  CRC-32C of the payload
//       16     4  CRC-32C of header bytes 0..15
//       20     …  payload
//
// Every message type has a fixed maximum payload size, so a receiver checks a
// length from the header alone, before it allocates or waits for the payload.
// The encoding is canonical: each message has exactly one byte representation,
// so encode(decode(frame)) == frame for every frame the decoder accepts.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "cluster/protocol/protocol_error.h"
#include "core/sha256.h"
#include "scene/frame_description.h"

namespace zenith::cluster {

/// Bumped on any change to the header or to any payload layout (docs/protocol.md, "Versioning").
inline constexpr std::uint16_t kProtocolVersion = 5;
inline constexpr std::array<std::uint8_t, 4> kMagic = {'Z', 'N', 'T', 'H'};
inline constexpr std::size_t kHeaderBytes = 20;

// Field limits.
inline constexpr std::size_t kMaxNameBytes = 64;      ///< cluster, node and body names (UTF-8 bytes)
inline constexpr std::size_t kMaxReasonBytes = 1024;  ///< Reject / Goodbye text (UTF-8 bytes)
using scene::kMaxAtmospheres;                         ///< FrameState atmosphere table references
using scene::kMaxWavelengths;                         ///< FrameState sun irradiance samples
inline constexpr std::size_t kMaxTableChunkBytes = std::size_t{1} << 20;      ///< 1 MiB per TableChunk
inline constexpr std::uint64_t kMaxTableTotalBytes = std::uint64_t{1} << 31;  ///< 2 GiB per table set
inline constexpr std::size_t kMaxDefinitionBytes = std::size_t{256} << 10;    ///< 256 KiB of atmosphere JSON
inline constexpr std::uint16_t kMaxThumbnailEdgePx = 64;  ///< a Thumbnail's width and height, at most
/// Tolerance on |q| − 1 and |sun direction| − 1 accepted from the wire.
using scene::kUnitTolerance;

using Digest = core::Sha256Digest;           ///< SHA-256 / HMAC-SHA256 output
using Nonce = std::array<std::uint8_t, 32>;  ///< handshake nonce (RAND_bytes)

/// 64 lowercase hex digits (core/sha256.h).
using core::to_hex;
/// The first 12 hex digits and "…": a table version in log lines.
std::string short_hex(const Digest& digest);
/// Parses 64 hex digits (either case); throws std::invalid_argument otherwise (core/sha256.h).
using core::digest_from_hex;

/// Wire values of the message types. Values are never reused.
enum class MessageType : std::uint16_t {
  hello = 1,                   ///< node → master
  challenge = 2,               ///< master → node
  authenticate = 3,            ///< node → master
  welcome = 4,                 ///< master → node
  reject = 5,                  ///< master → node, then close
  frame_state = 16,            ///< master → node, once per frame
  render_done = 17,            ///< node → master
  present = 18,                ///< master → node: every node is done, swap now
  preview_request = 19,        ///< master → node, before a FrameState: send thumbnails of that frame
  thumbnail = 20,              ///< node → master, before the RenderDone of a frame the master asked thumbnails of
  frame_schedule = 21,         ///< master → node, right before a FrameState: when to present it (scheduled frames)
  link_check = 22,             ///< master → node, from `zenith cluster check`: measure the link
  link_fill = 23,              ///< master → node: bytes of the link check's throughput measurement
  link_report = 24,            ///< node → master: what the node measured of the link check
  table_announce = 32,         ///< master → node
  table_chunk = 33,            ///< master → node
  table_ready = 34,            ///< node → master
  atmosphere_definition = 35,  ///< master → node, before the TableAnnounce of a set
  heartbeat = 48,              ///< both ways
  goodbye = 49,                ///< both ways, then close
  clock_ping = 50,             ///< node → master, in a datagram: the node's clock (clock offset, link check)
  clock_pong = 51,             ///< master → node, in a datagram: the ping answered with the master's clock
};
/// "Hello", "FrameState", ...; "unknown" for values outside the enum.
const char* to_string(MessageType type);
/// The type's largest valid payload in bytes, or nullopt when `type_value` is no MessageType.
std::optional<std::size_t> max_payload_bytes(std::uint16_t type_value);

// ---- handshake -------------------------------------------------------------

/// What the peer that opens a connection is to the master (Hello.role; docs/protocol.md, "Roles").
enum class PeerRole : std::uint8_t {
  node = 0,     ///< a render node: takes part in the frame barrier
  standby = 1,  ///< a standby master: follows every frame and table version, never renders
};
/// "node", "standby".
const char* to_string(PeerRole role);

/// Opens a connection. The node proves the shared secret in Authenticate.
struct Hello {
  std::uint16_t protocol_version = kProtocolVersion;  ///< must equal the header's (and kProtocolVersion)
  std::string cluster_name;                           ///< 1..kMaxNameBytes UTF-8 bytes; must match the master's
  std::string node_name;           ///< 1..kMaxNameBytes UTF-8 bytes; unique in the cluster (a standby: standby_name())
  Nonce node_nonce{};              ///< fresh random bytes
  PeerRole role = PeerRole::node;  ///< 0 node, 1 standby; other values are malformed
  /// Random per process, the same on every connection the process makes: the
  /// master tells a node that rejoins after a drop (the same id: it replaces
  /// its old connection) from another process using a name already connected
  /// (another id: refused with duplicate_node). Version 4.
  std::uint64_t instance_id = 0;
  bool operator==(const Hello&) const = default;
};
struct Challenge {
  Nonce master_nonce{};  ///< fresh random bytes
  bool operator==(const Challenge&) const = default;
};
struct Authenticate {
  Digest node_mac{};  ///< handshake.h: node_mac()
  bool operator==(const Authenticate&) const = default;
};
/// The master accepts the node and proves the secret in turn (mutual authentication).
struct Welcome {
  std::uint32_t node_id = 0;                ///< assigned by the master for this connection
  Digest master_mac{};                      ///< handshake.h: master_mac()
  std::uint64_t current_frame = 0;          ///< the frame the master is at
  std::uint32_t heartbeat_interval_ms = 0;  ///< each side sends a Heartbeat at least this often
  std::uint32_t barrier_timeout_ms = 0;     ///< a node not done within this is dropped from the frame
  /// The master's steady clock when it sent the Welcome (ns): the node's
  /// first estimate of the clock offset, good to the one-way delay, until
  /// its ClockPings give a better one (cluster/link/clock_sync.h). Version 5.
  std::uint64_t master_time_ns = 0;
  bool operator==(const Welcome&) const = default;
};
/// Reason codes of Reject. Unknown values are kept as they are (a newer peer
/// may send them) and read as `unspecified`.
enum class RejectReason : std::uint16_t {
  unspecified = 0,
  unsupported_version = 1,
  wrong_cluster = 2,
  authentication_failed = 3,
  duplicate_node = 4,
  protocol_error = 5,
  shutting_down = 6,
  wrong_role = 7,  ///< a standby the master has no place for (no standby configured, another standby's name)
};
struct Reject {
  RejectReason reason = RejectReason::unspecified;
  std::string text;  ///< ≤ kMaxReasonBytes UTF-8 bytes, for the log
  bool operator==(const Reject&) const = default;
};

// ---- frames ----------------------------------------------------------------

/// Bits of FrameState::render_flags (scene/frame_description.h). Bits
/// outside kKnownRenderFlags must be 0.
using scene::kKnownRenderFlags;
using scene::kRenderBodies;
using scene::kRenderEclipses;
using scene::kRenderLimbDarkening;
using scene::kRenderMultipleScattering;
using scene::kRenderSunDisc;
using scene::RenderFlag;

/// Which lookup-table set an atmosphere uses, from which frame on. body_name:
/// 1..kMaxNameBytes UTF-8 bytes.
using AtmosphereTableRef = scene::AtmosphereTableRef;

/// Everything a node needs to render one frame: the frame's description, which
/// the protocol serializes field by field (docs/protocol.md; wire order of the
/// camera orientation w, x, y, z). Every f64 must be finite.
using FrameState = scene::FrameDescription;

/// A node's frame is ready to present; with it, how its presents went so far
/// (render/window/present_clock.h): the console's late frames per node.
struct RenderDone {
  std::uint64_t frame = 0;
  double render_ms = 0.0;           ///< finite, ≥ 0
  std::uint64_t presents = 0;       ///< frames this node's process presented in windows so far (0 headless)
  std::uint64_t late_presents = 0;  ///< of those, presented late (a missed vblank); ≤ presents
  double present_ms = 0.0;  ///< its last present: Present's arrival to the completed swap (ms, ≥ 0; 0 headless)
  /// Scheduled frames this node did not present so far in this connection:
  /// they came after their moment, or not at all (cluster/node/present_schedule.h). Version 5.
  std::uint64_t missed_frames = 0;
  bool operator==(const RenderDone&) const = default;
};
struct Present {
  std::uint64_t frame = 0;
  bool operator==(const Present&) const = default;
};
/// Master → node, right before the FrameState of `frame` when the frames are
/// scheduled (docs/cluster.md, "The frame schedule"): present that frame when
/// the master's steady clock reads `present_at_ns` (the node maps it to its
/// own clock), whether or not any other node has rendered it. No Present
/// follows. `period_ns` is the schedule's frame period. Version 5.
struct FrameSchedule {
  std::uint64_t frame = 0;
  std::uint64_t present_at_ns = 0;  ///< the master's steady clock (ns)
  std::uint64_t period_ns = 0;      ///< in [kMinFramePeriodNs, kMaxFramePeriodNs]
  bool operator==(const FrameSchedule&) const = default;
};
/// A frame period the schedule may have: 250 Hz to 0.01 Hz (every timing.frame_rate_hz,
/// cluster/link/cluster_config.h).
inline constexpr std::uint64_t kMinFramePeriodNs = 4'000'000, kMaxFramePeriodNs = 100'000'000'000;

/// Master → node, right before the FrameState of `frame`: send a thumbnail
/// of every output of that frame (at most `edge_px` on its longer side) with
/// its RenderDone, for the operator console's dome preview. Never sent while
/// the preview is off, so it costs nothing then.
struct PreviewRequest {
  std::uint64_t frame = 0;
  std::uint16_t edge_px = kMaxThumbnailEdgePx;  ///< 1..kMaxThumbnailEdgePx
  bool operator==(const PreviewRequest&) const = default;
};
/// Node → master, before the RenderDone of a frame a PreviewRequest named:
/// one output of it, box-filtered down, as displayed (tone mapped, blended),
/// 8-bit sRGB, rows top to bottom, RGB interleaved.
struct Thumbnail {
  std::uint64_t frame = 0;
  std::string output;             ///< 1..kMaxNameBytes UTF-8 bytes: the output's name in the viewport config
  std::uint16_t width_px = 0;     ///< 1..kMaxThumbnailEdgePx
  std::uint16_t height_px = 0;    ///< 1..kMaxThumbnailEdgePx
  std::vector<std::uint8_t> rgb;  ///< width_px · height_px · 3 bytes
  bool operator==(const Thumbnail&) const = default;
};

// ---- lookup-table distribution ---------------------------------------------

/// A table set (the cache file of atmosphere/lut/table_cache.h) is about to be sent.
struct TableAnnounce {
  Digest table_hash{};            ///< identity of the set (lookup_table_hash)
  std::uint64_t total_bytes = 0;  ///< 1..kMaxTableTotalBytes
  std::uint32_t chunk_bytes = 0;  ///< 1..kMaxTableChunkBytes; every chunk but the last has this size
  std::uint32_t chunk_count = 0;  ///< = ceil(total_bytes / chunk_bytes)
  Digest content_sha256{};        ///< SHA-256 of the whole content; the node verifies it before TableReady
  bool operator==(const TableAnnounce&) const = default;
};
struct TableChunk {
  Digest table_hash{};
  std::uint32_t index = 0;          ///< 0..chunk_count−1
  std::vector<std::uint8_t> bytes;  ///< 1..kMaxTableChunkBytes
  bool operator==(const TableChunk&) const = default;
};
/// Node → master: the set arrived, its SHA-256 matched and it is cached.
struct TableReady {
  Digest table_hash{};
  bool operator==(const TableReady&) const = default;
};

/// Master → node, before a table set is announced: the parameters that shape
/// it, so a node renders any version the master prepares — a preset, a file
/// that exists only on the master's machine, a step of a show's parameter
/// track (docs/protocol.md, "Atmosphere definitions"). The node resolves the
/// parameters at its scene's wavelengths and refuses the definition unless
/// their lookup-table hash equals `table_hash`.
struct AtmosphereDefinition {
  std::string body_name;        ///< 1..kMaxNameBytes UTF-8 bytes; the scene's body
  Digest table_hash{};          ///< atmosphere::lookup_table_hash of the resolved parameters
  std::string parameters_json;  ///< 2..kMaxDefinitionBytes UTF-8 bytes: a JSON object (an atmosphere file's content)
  bool operator==(const AtmosphereDefinition&) const = default;
};

// ---- liveness --------------------------------------------------------------

struct Heartbeat {
  std::uint64_t sent_time_ns = 0;  ///< sender's steady clock (for round-trip time only)
  bool operator==(const Heartbeat&) const = default;
};
struct Goodbye {
  std::string reason;  ///< ≤ kMaxReasonBytes UTF-8 bytes
  bool operator==(const Goodbye&) const = default;
};
/// Node → master in a datagram (cluster/protocol/datagram.h), a few times a
/// second: the node's steady clock when it sent it (t1). Version 5.
struct ClockPing {
  std::uint64_t node_sent_ns = 0;
  bool operator==(const ClockPing&) const = default;
};
/// Master → node in a datagram, at once: the ping's t1 echoed, and the
/// master's steady clock when the ping arrived (t2) and when this left (t3).
/// With its arrival (t4) the node has one sample of the clock offset
/// ((t2 − t1) + (t3 − t4)) / 2 and of the round trip (t4 − t1) − (t3 − t2). Version 5.
struct ClockPong {
  std::uint64_t node_sent_ns = 0;
  std::uint64_t master_received_ns = 0;
  std::uint64_t master_sent_ns = 0;  ///< ≥ master_received_ns
  bool operator==(const ClockPong&) const = default;
};

// ---- the link check (`zenith cluster check`; docs/cluster.md, "Checking the network") ----

/// Master → node, right after Welcome, from `zenith cluster check` instead of
/// a show: send a ClockPing every `ping_interval_us` for `duration_ms` (its
/// round trips, losses and clock), then take `fill_bytes` of LinkFill (the
/// throughput toward the node) and answer with a LinkReport. Version 5.
struct LinkCheck {
  std::uint32_t duration_ms = 0;       ///< [kMinLinkCheckMs, kMaxLinkCheckMs]
  std::uint32_t ping_interval_us = 0;  ///< [kMinLinkPingIntervalUs, kMaxLinkPingIntervalUs]
  std::uint64_t fill_bytes = 0;        ///< [0, kMaxLinkFillBytes]
  bool operator==(const LinkCheck&) const = default;
};
inline constexpr std::uint32_t kMinLinkCheckMs = 100, kMaxLinkCheckMs = 60'000;
inline constexpr std::uint32_t kMinLinkPingIntervalUs = 1'000, kMaxLinkPingIntervalUs = 100'000;
inline constexpr std::uint64_t kMaxLinkFillBytes = std::uint64_t{1} << 30;  ///< 1 GiB
/// Master → node after a LinkCheck's pings: `bytes` of no meaning, numbered
/// from 0, until the check's fill_bytes have been sent.
struct LinkFill {
  std::uint32_t index = 0;
  std::vector<std::uint8_t> bytes;  ///< 1..kMaxTableChunkBytes
  bool operator==(const LinkFill&) const = default;
};
/// Node → master, once the LinkCheck's pings and fill are done: what the
/// node measured (cluster/node/link_check_answer.h). Times in ns of the
/// node's steady clock unless named otherwise. Version 5.
struct LinkReport {
  std::uint32_t pings_sent = 0;      ///< ClockPings of the check
  std::uint32_t pongs_received = 0;  ///< distinct ClockPongs answering them (≤ pings_sent)
  std::uint64_t first_ping_ns = 0;   ///< the check's first ping (≤ last_ping_ns)
  std::uint64_t last_ping_ns = 0;
  /// The answered pings' round trips δ = (t4 − t1) − (t3 − t2) (cluster/link/clock_sync.h):
  /// least, median, 99th percentile, largest (non-decreasing; all 0 without a pong).
  std::uint64_t round_trip_min_ns = 0, round_trip_p50_ns = 0, round_trip_p99_ns = 0, round_trip_max_ns = 0;
  std::uint64_t node_steady_ns = 0;        ///< the node's steady clock when it wrote the report
  std::uint64_t master_steady_ns = 0;      ///< the master's steady clock then, as the node's ClockSync has it
  std::uint64_t node_wall_ns = 0;          ///< the node's wall clock then (CLOCK_REALTIME, ns since 1970)
  std::uint64_t clock_uncertainty_ns = 0;  ///< the estimate's bound: half the least round trip
  double clock_drift_ppm = 0.0;            ///< master − node rate; finite, |·| ≤ 10⁶
  std::uint32_t clock_steps = 0;           ///< times the estimate started afresh (a clock stepped)
  std::uint64_t fill_bytes = 0;            ///< LinkFill bytes received
  std::uint64_t fill_timed_bytes = 0;      ///< of those, the ones after the first LinkFill (≤ fill_bytes)
  std::uint64_t fill_ns = 0;               ///< the first LinkFill's arrival to the last's
  bool operator==(const LinkReport&) const = default;
};

using Message =
    std::variant<Hello, Challenge, Authenticate, Welcome, Reject, FrameState, RenderDone, Present, TableAnnounce,
                 TableChunk, TableReady, Heartbeat, Goodbye, AtmosphereDefinition, PreviewRequest, Thumbnail,
                 FrameSchedule, ClockPing, ClockPong, LinkCheck, LinkFill, LinkReport>;

MessageType message_type(const Message& message);

/// The payload alone. Throws std::invalid_argument / std::length_error naming
/// the field when `message` breaks a limit the decoder would refuse.
std::vector<std::uint8_t> encode_payload(const Message& message);
/// Header + payload, ready for the socket. Same errors as encode_payload.
std::vector<std::uint8_t> encode(const Message& message);
/// Parses one payload of `type_value`. Throws ProtocolError (unknown_type,
/// malformed_payload, trailing_bytes, unsupported_version for Hello) naming the field.
Message decode_payload(std::uint16_t type_value, std::span<const std::uint8_t> payload);

/// A validated frame header.
struct FrameHeader {
  MessageType type{};
  std::uint32_t payload_bytes = 0;
  std::uint32_t payload_crc32c = 0;
};
/// Checks, in this order, magic, version, the header's own CRC-32C, type and
/// length (against the type's maximum) of a header. Throws ProtocolError
/// (bad_magic, unsupported_version, crc_mismatch, unknown_type, oversized).
FrameHeader parse_header(std::span<const std::uint8_t, kHeaderBytes> header);

/// The largest max_payload_bytes over all types.
std::size_t largest_max_payload_bytes();

}  // namespace zenith::cluster
