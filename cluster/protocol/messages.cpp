#include "cluster/protocol/messages.h"

#include <cmath>
#include <concepts>
#include <cstdio>
#include <stdexcept>
#include <type_traits>

#include "cluster/protocol/byte_io.h"
#include "cluster/protocol/crc32c.h"

namespace zenith::cluster {
namespace {

// ---- sizes -------------------------------------------------------------------

constexpr std::size_t kStringMax(std::size_t max_bytes) { return 2 + max_bytes; }
constexpr std::size_t kDigestBytes = 32;

constexpr std::size_t kHelloMax = 2 + kStringMax(kMaxNameBytes) * 2 + kDigestBytes + 1 + 8;
constexpr std::size_t kWelcomeMax = 4 + kDigestBytes + 8 + 4 + 4 + 8;
constexpr std::size_t kRejectMax = 2 + kStringMax(kMaxReasonBytes);
constexpr std::size_t kAtmosphereRefMax = kStringMax(kMaxNameBytes) + kDigestBytes + 8;
/// FrameState's sky fields (scene::SkyFrame): flags u8, UTC Julian date 2 × f64, catalogue identity.
constexpr std::size_t kSkyFrameBytes = 1 + 8 + 8 + kDigestBytes;
constexpr std::size_t kFrameStateMax = 8 + 8 + 3 * 8 + 4 * 8 + 8 + 3 * 8 + 8 + 1 + kMaxWavelengths * 8 + 1 +
                                       kMaxAtmospheres * kAtmosphereRefMax + 4 + 8 + 3 * 8 + kSkyFrameBytes;
constexpr std::size_t kTableAnnounceMax = kDigestBytes + 8 + 4 + 4 + kDigestBytes;
constexpr std::size_t kTableChunkMax = kDigestBytes + 4 + 4 + kMaxTableChunkBytes;
constexpr std::size_t kGoodbyeMax = kStringMax(kMaxReasonBytes);
constexpr std::size_t kDefinitionMax = kStringMax(kMaxNameBytes) + kDigestBytes + 4 + kMaxDefinitionBytes;
constexpr std::size_t kPreviewRequestMax = 8 + 2;
constexpr std::size_t kThumbnailMax =
    8 + kStringMax(kMaxNameBytes) + 2 + 2 + 4 + std::size_t{kMaxThumbnailEdgePx} * kMaxThumbnailEdgePx * 3;
constexpr std::size_t kLinkFillMax = 4 + 4 + kMaxTableChunkBytes;
constexpr std::size_t kLinkReportMax = 4 + 4 + 2 * 8 + 4 * 8 + 4 * 8 + 8 + 4 + 3 * 8;
static_assert(kThumbnailMax == 12370);
static_assert(kLinkReportMax == 124);
static_assert(kFrameStateMax == 1559);
static_assert(kTableChunkMax == 1048616);

/// The sky's dates a FrameState may carry: UTC exists from 1960 (ERFA), the
/// ephemerides are good to 2100.
constexpr double kSkyFirstJulianDate = 2436934.5, kSkyLastJulianDate = 2488069.5;

// ---- validation shared by the encoder (std::invalid_argument) and the decoder (ProtocolError) ----

struct Check {
  bool decoding;
  void operator()(bool ok, const std::string& detail) const {
    if (ok) return;
    if (decoding) throw ProtocolError(ProtocolErrorCode::malformed_payload, detail);
    throw std::invalid_argument("cannot encode: " + detail);
  }
};

bool is_unit(double length) { return std::isfinite(length) && std::abs(length - 1.0) <= kUnitTolerance; }

void validate(const Hello& m, const Check& check) {
  check(m.protocol_version == kProtocolVersion, "Hello.protocol_version: " + std::to_string(m.protocol_version) +
                                                    ", this build speaks " + std::to_string(kProtocolVersion));
  check(!m.cluster_name.empty(), "Hello.cluster_name: empty");
  check(!m.node_name.empty(), "Hello.node_name: empty");
  check(m.role == PeerRole::node || m.role == PeerRole::standby,
        "Hello.role: " + std::to_string(static_cast<int>(m.role)) + ", must be 0 (node) or 1 (standby)");
}
void validate(const FrameState& m, const Check& check) {
  const auto finite = [&](double v, const char* field) {
    check(std::isfinite(v), std::string("FrameState.") + field + ": not finite");
  };
  finite(m.show_time_s, "show_time_s");
  for (int i = 0; i < 3; ++i) finite(m.camera_position_m[i], "camera_position_m");
  for (int i = 0; i < 4; ++i) finite(m.camera_orientation[i], "camera_orientation");
  finite(m.exposure, "exposure");
  for (int i = 0; i < 3; ++i) finite(m.sun_direction[i], "sun_direction");
  finite(m.sun_angular_radius_rad, "sun_angular_radius_rad");
  check(is_unit(glm::length(m.camera_orientation)), "FrameState.camera_orientation: not a unit quaternion");
  check(m.exposure > 0.0, "FrameState.exposure: must be > 0");
  check(is_unit(glm::length(m.sun_direction)), "FrameState.sun_direction: not a unit vector");
  check(m.sun_angular_radius_rad >= 0.0, "FrameState.sun_angular_radius_rad: must be >= 0");
  check(m.sun_irradiance_W_m2_nm.size() <= kMaxWavelengths,
        "FrameState.sun_irradiance_W_m2_nm: " + std::to_string(m.sun_irradiance_W_m2_nm.size()) + " values, at most " +
            std::to_string(kMaxWavelengths));
  for (double e : m.sun_irradiance_W_m2_nm)
    check(std::isfinite(e) && e >= 0.0, "FrameState.sun_irradiance_W_m2_nm: value not finite or < 0");
  check(m.atmospheres.size() <= kMaxAtmospheres, "FrameState.atmospheres: " + std::to_string(m.atmospheres.size()) +
                                                     " entries, at most " + std::to_string(kMaxAtmospheres));
  for (const auto& a : m.atmospheres) check(!a.body_name.empty(), "FrameState.atmospheres[].body_name: empty");
  check((m.render_flags & ~kKnownRenderFlags) == 0, "FrameState.render_flags: unknown bits set");
  finite(m.fade.level, "fade_level");
  for (int i = 0; i < 3; ++i) finite(m.fade.colour[i], "fade_colour");
  check(m.fade.level >= 0.0 && m.fade.level <= 1.0, "FrameState.fade_level: must be in [0, 1]");
  for (int i = 0; i < 3; ++i)
    check(m.fade.colour[i] >= 0.0 && m.fade.colour[i] <= 1.0,
          "FrameState.fade_colour: each component must be in [0, 1]");
  finite(m.sky.utc_jd1, "sky.utc_jd1");
  finite(m.sky.utc_jd2, "sky.utc_jd2");
  if (m.sky.has_time) {
    const double jd = m.sky.utc_jd1 + m.sky.utc_jd2;
    check(jd >= kSkyFirstJulianDate && jd <= kSkyLastJulianDate,
          "FrameState.sky.utc_jd: " + std::to_string(jd) + " outside [2436934.5, 2488069.5] (1960–2100)");
  } else {
    check(m.sky.utc_jd1 == 0.0 && m.sky.utc_jd2 == 0.0, "FrameState.sky.utc_jd: set without the has_time flag");
  }
}
void validate(const RenderDone& m, const Check& check) {
  check(std::isfinite(m.render_ms) && m.render_ms >= 0.0, "RenderDone.render_ms: not finite or < 0");
  check(m.late_presents <= m.presents, "RenderDone.late_presents: " + std::to_string(m.late_presents) +
                                           ", more than presents = " + std::to_string(m.presents));
  check(std::isfinite(m.present_ms) && m.present_ms >= 0.0, "RenderDone.present_ms: not finite or < 0");
}
void validate(const TableAnnounce& m, const Check& check) {
  check(m.total_bytes >= 1 && m.total_bytes <= kMaxTableTotalBytes,
        "TableAnnounce.total_bytes: " + std::to_string(m.total_bytes) + " outside [1, " +
            std::to_string(kMaxTableTotalBytes) + "]");
  check(m.chunk_bytes >= 1 && m.chunk_bytes <= kMaxTableChunkBytes,
        "TableAnnounce.chunk_bytes: " + std::to_string(m.chunk_bytes) + " outside [1, " +
            std::to_string(kMaxTableChunkBytes) + "]");
  if (m.chunk_bytes >= 1) {
    const std::uint64_t expected = (m.total_bytes + m.chunk_bytes - 1) / m.chunk_bytes;
    check(m.chunk_count == expected, "TableAnnounce.chunk_count: " + std::to_string(m.chunk_count) +
                                         ", expected ceil(total_bytes / chunk_bytes) = " + std::to_string(expected));
  }
}
void validate(const TableChunk& m, const Check& check) {
  check(!m.bytes.empty() && m.bytes.size() <= kMaxTableChunkBytes,
        "TableChunk.bytes: " + std::to_string(m.bytes.size()) + " bytes outside [1, " +
            std::to_string(kMaxTableChunkBytes) + "]");
}
void validate(const AtmosphereDefinition& m, const Check& check) {
  check(!m.body_name.empty(), "AtmosphereDefinition.body_name: empty");
  // Only the shape is checked here: the node parses the JSON and verifies its hash.
  check(m.parameters_json.size() >= 2 && m.parameters_json.front() == '{' && m.parameters_json.back() == '}',
        "AtmosphereDefinition.parameters_json: not a JSON object ({...})");
}
void validate(const PreviewRequest& m, const Check& check) {
  check(m.edge_px >= 1 && m.edge_px <= kMaxThumbnailEdgePx, "PreviewRequest.edge_px: " + std::to_string(m.edge_px) +
                                                                " outside [1, " + std::to_string(kMaxThumbnailEdgePx) +
                                                                "]");
}
void validate(const Thumbnail& m, const Check& check) {
  check(!m.output.empty(), "Thumbnail.output: empty");
  check(m.width_px >= 1 && m.width_px <= kMaxThumbnailEdgePx && m.height_px >= 1 && m.height_px <= kMaxThumbnailEdgePx,
        "Thumbnail size: " + std::to_string(m.width_px) + "x" + std::to_string(m.height_px) + ", each side in [1, " +
            std::to_string(kMaxThumbnailEdgePx) + "]");
  const std::size_t expected = std::size_t{m.width_px} * m.height_px * 3;
  check(m.rgb.size() == expected, "Thumbnail.rgb: " + std::to_string(m.rgb.size()) +
                                      " bytes, expected width · height · 3 = " + std::to_string(expected));
}
void validate(const FrameSchedule& m, const Check& check) {
  check(m.period_ns >= kMinFramePeriodNs && m.period_ns <= kMaxFramePeriodNs,
        "FrameSchedule.period_ns: " + std::to_string(m.period_ns) + " outside [" + std::to_string(kMinFramePeriodNs) +
            ", " + std::to_string(kMaxFramePeriodNs) + "] (250 Hz to 0.01 Hz)");
}
void validate(const ClockPong& m, const Check& check) {
  check(m.master_sent_ns >= m.master_received_ns,
        "ClockPong.master_sent_ns: " + std::to_string(m.master_sent_ns) +
            ", before master_received_ns = " + std::to_string(m.master_received_ns));
}
void validate(const LinkCheck& m, const Check& check) {
  check(m.duration_ms >= kMinLinkCheckMs && m.duration_ms <= kMaxLinkCheckMs,
        "LinkCheck.duration_ms: " + std::to_string(m.duration_ms) + " outside [" + std::to_string(kMinLinkCheckMs) +
            ", " + std::to_string(kMaxLinkCheckMs) + "]");
  check(m.ping_interval_us >= kMinLinkPingIntervalUs && m.ping_interval_us <= kMaxLinkPingIntervalUs,
        "LinkCheck.ping_interval_us: " + std::to_string(m.ping_interval_us) + " outside [" +
            std::to_string(kMinLinkPingIntervalUs) + ", " + std::to_string(kMaxLinkPingIntervalUs) + "]");
  check(m.fill_bytes <= kMaxLinkFillBytes,
        "LinkCheck.fill_bytes: " + std::to_string(m.fill_bytes) + " above " + std::to_string(kMaxLinkFillBytes));
}
void validate(const LinkFill& m, const Check& check) {
  check(!m.bytes.empty() && m.bytes.size() <= kMaxTableChunkBytes, "LinkFill.bytes: " + std::to_string(m.bytes.size()) +
                                                                       " bytes outside [1, " +
                                                                       std::to_string(kMaxTableChunkBytes) + "]");
}
void validate(const LinkReport& m, const Check& check) {
  check(m.pongs_received <= m.pings_sent, "LinkReport.pongs_received: " + std::to_string(m.pongs_received) +
                                              ", more than pings_sent = " + std::to_string(m.pings_sent));
  check(m.first_ping_ns <= m.last_ping_ns, "LinkReport.first_ping_ns: after last_ping_ns");
  check(m.round_trip_min_ns <= m.round_trip_p50_ns && m.round_trip_p50_ns <= m.round_trip_p99_ns &&
            m.round_trip_p99_ns <= m.round_trip_max_ns,
        "LinkReport.round_trip_*_ns: not min ≤ p50 ≤ p99 ≤ max");
  check(std::isfinite(m.clock_drift_ppm) && std::abs(m.clock_drift_ppm) <= 1e6,
        "LinkReport.clock_drift_ppm: not a finite value within ±10⁶");
  check(m.fill_timed_bytes <= m.fill_bytes, "LinkReport.fill_timed_bytes: more than fill_bytes");
}
template <class T>
void validate(const T&, const Check&) {}

// ---- fixed layouts: one list of fields for the writer and the reader ----------
//
// A message whose fields are all integers, doubles and digests lists them once,
// in wire order, with their names for errors; a field's C++ type is its wire
// type (byte_io.h: big-endian integers, IEEE doubles, a digest's 32 bytes).

struct FieldWriter {
  ByteWriter& w;
  void operator()(const std::uint16_t& v, const char*) { w.u16(v); }
  void operator()(const std::uint32_t& v, const char*) { w.u32(v); }
  void operator()(const std::uint64_t& v, const char*) { w.u64(v); }
  void operator()(const double& v, const char*) { w.f64(v); }
  void operator()(const Digest& v, const char*) { w.bytes(v); }
};
struct FieldReader {
  ByteReader& r;
  void operator()(std::uint16_t& v, const char* field) { v = r.u16(field); }
  void operator()(std::uint32_t& v, const char* field) { v = r.u32(field); }
  void operator()(std::uint64_t& v, const char* field) { v = r.u64(field); }
  void operator()(double& v, const char* field) { v = r.f64(field); }
  void operator()(Digest& v, const char* field) { v = r.array<32>(field); }
};

/// `M` is the message `T`, const or not (a layout serves the writer and the reader).
template <class M, class T>
concept MessageOf = std::same_as<std::remove_const_t<M>, T>;

template <class Io, MessageOf<Welcome> M>
void layout(Io&& io, M& m) {
  io(m.node_id, "Welcome.node_id");
  io(m.master_mac, "Welcome.master_mac");
  io(m.current_frame, "Welcome.current_frame");
  io(m.heartbeat_interval_ms, "Welcome.heartbeat_interval_ms");
  io(m.barrier_timeout_ms, "Welcome.barrier_timeout_ms");
  io(m.master_time_ns, "Welcome.master_time_ns");
}
template <class Io, MessageOf<FrameSchedule> M>
void layout(Io&& io, M& m) {
  io(m.frame, "FrameSchedule.frame");
  io(m.present_at_ns, "FrameSchedule.present_at_ns");
  io(m.period_ns, "FrameSchedule.period_ns");
}
template <class Io, MessageOf<ClockPing> M>
void layout(Io&& io, M& m) {
  io(m.node_sent_ns, "ClockPing.node_sent_ns");
}
template <class Io, MessageOf<ClockPong> M>
void layout(Io&& io, M& m) {
  io(m.node_sent_ns, "ClockPong.node_sent_ns");
  io(m.master_received_ns, "ClockPong.master_received_ns");
  io(m.master_sent_ns, "ClockPong.master_sent_ns");
}
template <class Io, MessageOf<LinkCheck> M>
void layout(Io&& io, M& m) {
  io(m.duration_ms, "LinkCheck.duration_ms");
  io(m.ping_interval_us, "LinkCheck.ping_interval_us");
  io(m.fill_bytes, "LinkCheck.fill_bytes");
}
template <class Io, MessageOf<LinkReport> M>
void layout(Io&& io, M& m) {
  io(m.pings_sent, "LinkReport.pings_sent");
  io(m.pongs_received, "LinkReport.pongs_received");
  io(m.first_ping_ns, "LinkReport.first_ping_ns");
  io(m.last_ping_ns, "LinkReport.last_ping_ns");
  io(m.round_trip_min_ns, "LinkReport.round_trip_min_ns");
  io(m.round_trip_p50_ns, "LinkReport.round_trip_p50_ns");
  io(m.round_trip_p99_ns, "LinkReport.round_trip_p99_ns");
  io(m.round_trip_max_ns, "LinkReport.round_trip_max_ns");
  io(m.node_steady_ns, "LinkReport.node_steady_ns");
  io(m.master_steady_ns, "LinkReport.master_steady_ns");
  io(m.node_wall_ns, "LinkReport.node_wall_ns");
  io(m.clock_uncertainty_ns, "LinkReport.clock_uncertainty_ns");
  io(m.clock_drift_ppm, "LinkReport.clock_drift_ppm");
  io(m.clock_steps, "LinkReport.clock_steps");
  io(m.fill_bytes, "LinkReport.fill_bytes");
  io(m.fill_timed_bytes, "LinkReport.fill_timed_bytes");
  io(m.fill_ns, "LinkReport.fill_ns");
}
template <class Io, MessageOf<RenderDone> M>
void layout(Io&& io, M& m) {
  io(m.frame, "RenderDone.frame");
  io(m.render_ms, "RenderDone.render_ms");
  io(m.presents, "RenderDone.presents");
  io(m.late_presents, "RenderDone.late_presents");
  io(m.present_ms, "RenderDone.present_ms");
  io(m.missed_frames, "RenderDone.missed_frames");
}
template <class Io, MessageOf<PreviewRequest> M>
void layout(Io&& io, M& m) {
  io(m.frame, "PreviewRequest.frame");
  io(m.edge_px, "PreviewRequest.edge_px");
}
template <class Io, MessageOf<TableAnnounce> M>
void layout(Io&& io, M& m) {
  io(m.table_hash, "TableAnnounce.table_hash");
  io(m.total_bytes, "TableAnnounce.total_bytes");
  io(m.chunk_bytes, "TableAnnounce.chunk_bytes");
  io(m.chunk_count, "TableAnnounce.chunk_count");
  io(m.content_sha256, "TableAnnounce.content_sha256");
}

template <class M>
concept HasLayout = requires(ByteWriter& w, const M& m) {
  layout(FieldWriter{w}, m);
};

template <HasLayout M>
M read_fields(ByteReader& r) {
  M m;
  layout(FieldReader{r}, m);
  return m;
}

// ---- writers -------------------------------------------------------------------

template <HasLayout M>
void write(ByteWriter& w, const M& m) {
  layout(FieldWriter{w}, m);
}

void write(ByteWriter& w, const Hello& m) {
  w.u16(m.protocol_version);
  w.string(m.cluster_name, kMaxNameBytes, "Hello.cluster_name");
  w.string(m.node_name, kMaxNameBytes, "Hello.node_name");
  w.bytes(m.node_nonce);
  w.u8(static_cast<std::uint8_t>(m.role));
  w.u64(m.instance_id);
}
void write(ByteWriter& w, const Challenge& m) { w.bytes(m.master_nonce); }
void write(ByteWriter& w, const Authenticate& m) { w.bytes(m.node_mac); }
void write(ByteWriter& w, const Reject& m) {
  w.u16(static_cast<std::uint16_t>(m.reason));
  w.string(m.text, kMaxReasonBytes, "Reject.text");
}
void write(ByteWriter& w, const FrameState& m) {
  w.u64(m.frame);
  w.f64(m.show_time_s);
  for (int i = 0; i < 3; ++i) w.f64(m.camera_position_m[i]);
  w.f64(m.camera_orientation.w);
  w.f64(m.camera_orientation.x);
  w.f64(m.camera_orientation.y);
  w.f64(m.camera_orientation.z);
  w.f64(m.exposure);
  for (int i = 0; i < 3; ++i) w.f64(m.sun_direction[i]);
  w.f64(m.sun_angular_radius_rad);
  w.u8(static_cast<std::uint8_t>(m.sun_irradiance_W_m2_nm.size()));
  for (double e : m.sun_irradiance_W_m2_nm) w.f64(e);
  w.u8(static_cast<std::uint8_t>(m.atmospheres.size()));
  for (const auto& a : m.atmospheres) {
    w.string(a.body_name, kMaxNameBytes, "FrameState.atmospheres[].body_name");
    w.bytes(a.table_hash);
    w.u64(a.effective_from_frame);
  }
  w.u32(m.render_flags);
  w.f64(m.fade.level);
  for (int i = 0; i < 3; ++i) w.f64(m.fade.colour[i]);
  w.u8(m.sky.has_time ? 1 : 0);
  w.f64(m.sky.utc_jd1);
  w.f64(m.sky.utc_jd2);
  w.bytes(m.sky.star_catalogue);
}
void write(ByteWriter& w, const Present& m) { w.u64(m.frame); }
void write(ByteWriter& w, const Thumbnail& m) {
  w.u64(m.frame);
  w.string(m.output, kMaxNameBytes, "Thumbnail.output");
  w.u16(m.width_px);
  w.u16(m.height_px);
  w.u32(static_cast<std::uint32_t>(m.rgb.size()));
  w.bytes(m.rgb);
}
void write(ByteWriter& w, const TableChunk& m) {
  w.bytes(m.table_hash);
  w.u32(m.index);
  w.u32(static_cast<std::uint32_t>(m.bytes.size()));
  w.bytes(m.bytes);
}
void write(ByteWriter& w, const LinkFill& m) {
  w.u32(m.index);
  w.u32(static_cast<std::uint32_t>(m.bytes.size()));
  w.bytes(m.bytes);
}
void write(ByteWriter& w, const TableReady& m) { w.bytes(m.table_hash); }
void write(ByteWriter& w, const AtmosphereDefinition& m) {
  w.string(m.body_name, kMaxNameBytes, "AtmosphereDefinition.body_name");
  w.bytes(m.table_hash);
  w.long_string(m.parameters_json, kMaxDefinitionBytes, "AtmosphereDefinition.parameters_json");
}
void write(ByteWriter& w, const Heartbeat& m) { w.u64(m.sent_time_ns); }
void write(ByteWriter& w, const Goodbye& m) { w.string(m.reason, kMaxReasonBytes, "Goodbye.reason"); }

// ---- readers -------------------------------------------------------------------

Hello read_hello(ByteReader& r) {
  Hello m;
  m.protocol_version = r.u16("Hello.protocol_version");
  if (m.protocol_version != kProtocolVersion)
    throw ProtocolError(ProtocolErrorCode::unsupported_version,
                        "Hello.protocol_version: " + std::to_string(m.protocol_version) + ", this build speaks " +
                            std::to_string(kProtocolVersion));
  m.cluster_name = r.string(kMaxNameBytes, "Hello.cluster_name");
  m.node_name = r.string(kMaxNameBytes, "Hello.node_name");
  m.node_nonce = r.array<32>("Hello.node_nonce");
  m.role = static_cast<PeerRole>(r.u8("Hello.role"));
  m.instance_id = r.u64("Hello.instance_id");
  return m;
}
FrameState read_frame_state(ByteReader& r) {
  FrameState m;
  m.frame = r.u64("FrameState.frame");
  m.show_time_s = r.f64("FrameState.show_time_s");
  for (int i = 0; i < 3; ++i) m.camera_position_m[i] = r.f64("FrameState.camera_position_m");
  m.camera_orientation.w = r.f64("FrameState.camera_orientation.w");
  m.camera_orientation.x = r.f64("FrameState.camera_orientation.x");
  m.camera_orientation.y = r.f64("FrameState.camera_orientation.y");
  m.camera_orientation.z = r.f64("FrameState.camera_orientation.z");
  m.exposure = r.f64("FrameState.exposure");
  for (int i = 0; i < 3; ++i) m.sun_direction[i] = r.f64("FrameState.sun_direction");
  m.sun_angular_radius_rad = r.f64("FrameState.sun_angular_radius_rad");
  const std::size_t wavelengths = r.u8("FrameState.sun_irradiance_W_m2_nm count");
  if (wavelengths > kMaxWavelengths)
    ByteReader::fail("FrameState.sun_irradiance_W_m2_nm count: " + std::to_string(wavelengths) + ", at most " +
                     std::to_string(kMaxWavelengths));
  m.sun_irradiance_W_m2_nm.reserve(wavelengths);
  for (std::size_t i = 0; i < wavelengths; ++i)
    m.sun_irradiance_W_m2_nm.push_back(r.f64("FrameState.sun_irradiance_W_m2_nm"));
  const std::size_t atmospheres = r.u8("FrameState.atmospheres count");
  if (atmospheres > kMaxAtmospheres)
    ByteReader::fail("FrameState.atmospheres count: " + std::to_string(atmospheres) + ", at most " +
                     std::to_string(kMaxAtmospheres));
  m.atmospheres.reserve(atmospheres);
  for (std::size_t i = 0; i < atmospheres; ++i) {
    AtmosphereTableRef a;
    a.body_name = r.string(kMaxNameBytes, "FrameState.atmospheres[].body_name");
    a.table_hash = r.array<32>("FrameState.atmospheres[].table_hash");
    a.effective_from_frame = r.u64("FrameState.atmospheres[].effective_from_frame");
    m.atmospheres.push_back(std::move(a));
  }
  m.render_flags = r.u32("FrameState.render_flags");
  m.fade.level = r.f64("FrameState.fade_level");
  for (int i = 0; i < 3; ++i) m.fade.colour[i] = r.f64("FrameState.fade_colour");
  const std::uint8_t sky_flags = r.u8("FrameState.sky.flags");
  if ((sky_flags & ~1u) != 0) ByteReader::fail("FrameState.sky.flags: unknown bits set");
  m.sky.has_time = (sky_flags & 1u) != 0;
  m.sky.utc_jd1 = r.f64("FrameState.sky.utc_jd1");
  m.sky.utc_jd2 = r.f64("FrameState.sky.utc_jd2");
  m.sky.star_catalogue = r.array<32>("FrameState.sky.star_catalogue");
  return m;
}
TableChunk read_table_chunk(ByteReader& r) {
  TableChunk m;
  m.table_hash = r.array<32>("TableChunk.table_hash");
  m.index = r.u32("TableChunk.index");
  const std::size_t length = r.u32("TableChunk.bytes length");
  if (length > kMaxTableChunkBytes)
    ByteReader::fail("TableChunk.bytes length: " + std::to_string(length) + ", at most " +
                     std::to_string(kMaxTableChunkBytes));
  auto view = r.bytes(length, "TableChunk.bytes");  // checked against the payload before copying
  m.bytes.assign(view.begin(), view.end());
  return m;
}

LinkFill read_link_fill(ByteReader& r) {
  LinkFill m;
  m.index = r.u32("LinkFill.index");
  const std::size_t length = r.u32("LinkFill.bytes length");
  if (length > kMaxTableChunkBytes)
    ByteReader::fail("LinkFill.bytes length: " + std::to_string(length) + ", at most " +
                     std::to_string(kMaxTableChunkBytes));
  auto view = r.bytes(length, "LinkFill.bytes");  // checked against the payload before copying
  m.bytes.assign(view.begin(), view.end());
  return m;
}

Thumbnail read_thumbnail(ByteReader& r) {
  Thumbnail m;
  m.frame = r.u64("Thumbnail.frame");
  m.output = r.string(kMaxNameBytes, "Thumbnail.output");
  m.width_px = r.u16("Thumbnail.width_px");
  m.height_px = r.u16("Thumbnail.height_px");
  const std::size_t length = r.u32("Thumbnail.rgb length");
  const std::size_t limit = std::size_t{kMaxThumbnailEdgePx} * kMaxThumbnailEdgePx * 3;
  if (length > limit)
    ByteReader::fail("Thumbnail.rgb length: " + std::to_string(length) + ", at most " + std::to_string(limit));
  auto view = r.bytes(length, "Thumbnail.rgb");  // checked against the payload before copying
  m.rgb.assign(view.begin(), view.end());
  return m;
}

Message read(MessageType type, ByteReader& r) {
  switch (type) {
    case MessageType::hello: return read_hello(r);
    case MessageType::challenge: return Challenge{r.array<32>("Challenge.master_nonce")};
    case MessageType::authenticate: return Authenticate{r.array<32>("Authenticate.node_mac")};
    case MessageType::welcome: return read_fields<Welcome>(r);
    case MessageType::reject: {
      Reject m;
      m.reason = static_cast<RejectReason>(r.u16("Reject.reason"));
      m.text = r.string(kMaxReasonBytes, "Reject.text");
      return m;
    }
    case MessageType::frame_state: return read_frame_state(r);
    case MessageType::render_done: return read_fields<RenderDone>(r);
    case MessageType::present: return Present{r.u64("Present.frame")};
    case MessageType::preview_request: return read_fields<PreviewRequest>(r);
    case MessageType::thumbnail: return read_thumbnail(r);
    case MessageType::table_announce: return read_fields<TableAnnounce>(r);
    case MessageType::table_chunk: return read_table_chunk(r);
    case MessageType::table_ready: return TableReady{r.array<32>("TableReady.table_hash")};
    case MessageType::atmosphere_definition: {
      AtmosphereDefinition m;
      m.body_name = r.string(kMaxNameBytes, "AtmosphereDefinition.body_name");
      m.table_hash = r.array<32>("AtmosphereDefinition.table_hash");
      m.parameters_json = r.long_string(kMaxDefinitionBytes, "AtmosphereDefinition.parameters_json");
      return m;
    }
    case MessageType::heartbeat: return Heartbeat{r.u64("Heartbeat.sent_time_ns")};
    case MessageType::goodbye: return Goodbye{r.string(kMaxReasonBytes, "Goodbye.reason")};
    case MessageType::frame_schedule: return read_fields<FrameSchedule>(r);
    case MessageType::clock_ping: return read_fields<ClockPing>(r);
    case MessageType::clock_pong: return read_fields<ClockPong>(r);
    case MessageType::link_check: return read_fields<LinkCheck>(r);
    case MessageType::link_fill: return read_link_fill(r);
    case MessageType::link_report: return read_fields<LinkReport>(r);
  }
  throw ProtocolError(ProtocolErrorCode::unknown_type, "message type " + std::to_string(static_cast<int>(type)));
}

template <class T>
constexpr MessageType type_of() {
  if constexpr (std::is_same_v<T, Hello>)
    return MessageType::hello;
  else if constexpr (std::is_same_v<T, Challenge>)
    return MessageType::challenge;
  else if constexpr (std::is_same_v<T, Authenticate>)
    return MessageType::authenticate;
  else if constexpr (std::is_same_v<T, Welcome>)
    return MessageType::welcome;
  else if constexpr (std::is_same_v<T, Reject>)
    return MessageType::reject;
  else if constexpr (std::is_same_v<T, FrameState>)
    return MessageType::frame_state;
  else if constexpr (std::is_same_v<T, RenderDone>)
    return MessageType::render_done;
  else if constexpr (std::is_same_v<T, Present>)
    return MessageType::present;
  else if constexpr (std::is_same_v<T, TableAnnounce>)
    return MessageType::table_announce;
  else if constexpr (std::is_same_v<T, TableChunk>)
    return MessageType::table_chunk;
  else if constexpr (std::is_same_v<T, TableReady>)
    return MessageType::table_ready;
  else if constexpr (std::is_same_v<T, Heartbeat>)
    return MessageType::heartbeat;
  else if constexpr (std::is_same_v<T, AtmosphereDefinition>)
    return MessageType::atmosphere_definition;
  else if constexpr (std::is_same_v<T, PreviewRequest>)
    return MessageType::preview_request;
  else if constexpr (std::is_same_v<T, Thumbnail>)
    return MessageType::thumbnail;
  else if constexpr (std::is_same_v<T, FrameSchedule>)
    return MessageType::frame_schedule;
  else if constexpr (std::is_same_v<T, ClockPing>)
    return MessageType::clock_ping;
  else if constexpr (std::is_same_v<T, ClockPong>)
    return MessageType::clock_pong;
  else if constexpr (std::is_same_v<T, LinkCheck>)
    return MessageType::link_check;
  else if constexpr (std::is_same_v<T, LinkFill>)
    return MessageType::link_fill;
  else if constexpr (std::is_same_v<T, LinkReport>)
    return MessageType::link_report;
  else {
    static_assert(std::is_same_v<T, Goodbye>);
    return MessageType::goodbye;
  }
}

void put_be32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (24 - 8 * i));
}

}  // namespace

std::string short_hex(const Digest& digest) { return to_hex(digest).substr(0, 12) + "…"; }

const char* to_string(PeerRole role) {
  switch (role) {
    case PeerRole::node: return "node";
    case PeerRole::standby: return "standby";
  }
  return "unknown role";
}

const char* to_string(MessageType type) {
  switch (type) {
    case MessageType::hello: return "Hello";
    case MessageType::challenge: return "Challenge";
    case MessageType::authenticate: return "Authenticate";
    case MessageType::welcome: return "Welcome";
    case MessageType::reject: return "Reject";
    case MessageType::frame_state: return "FrameState";
    case MessageType::render_done: return "RenderDone";
    case MessageType::present: return "Present";
    case MessageType::preview_request: return "PreviewRequest";
    case MessageType::thumbnail: return "Thumbnail";
    case MessageType::table_announce: return "TableAnnounce";
    case MessageType::table_chunk: return "TableChunk";
    case MessageType::table_ready: return "TableReady";
    case MessageType::atmosphere_definition: return "AtmosphereDefinition";
    case MessageType::heartbeat: return "Heartbeat";
    case MessageType::goodbye: return "Goodbye";
    case MessageType::frame_schedule: return "FrameSchedule";
    case MessageType::clock_ping: return "ClockPing";
    case MessageType::clock_pong: return "ClockPong";
    case MessageType::link_check: return "LinkCheck";
    case MessageType::link_fill: return "LinkFill";
    case MessageType::link_report: return "LinkReport";
  }
  return "unknown";
}

std::optional<std::size_t> max_payload_bytes(std::uint16_t type_value) {
  switch (static_cast<MessageType>(type_value)) {
    case MessageType::hello: return kHelloMax;
    case MessageType::challenge: return kDigestBytes;
    case MessageType::authenticate: return kDigestBytes;
    case MessageType::welcome: return kWelcomeMax;
    case MessageType::reject: return kRejectMax;
    case MessageType::frame_state: return kFrameStateMax;
    case MessageType::render_done: return 48;
    case MessageType::present: return 8;
    case MessageType::preview_request: return kPreviewRequestMax;
    case MessageType::thumbnail: return kThumbnailMax;
    case MessageType::table_announce: return kTableAnnounceMax;
    case MessageType::table_chunk: return kTableChunkMax;
    case MessageType::table_ready: return kDigestBytes;
    case MessageType::atmosphere_definition: return kDefinitionMax;
    case MessageType::heartbeat: return 8;
    case MessageType::goodbye: return kGoodbyeMax;
    case MessageType::frame_schedule: return 24;
    case MessageType::clock_ping: return 8;
    case MessageType::clock_pong: return 24;
    case MessageType::link_check: return 16;
    case MessageType::link_fill: return kLinkFillMax;
    case MessageType::link_report: return kLinkReportMax;
  }
  return std::nullopt;
}

std::size_t largest_max_payload_bytes() { return kTableChunkMax; }

MessageType message_type(const Message& message) {
  return std::visit([](const auto& m) { return type_of<std::decay_t<decltype(m)>>(); }, message);
}

std::vector<std::uint8_t> encode_payload(const Message& message) {
  std::vector<std::uint8_t> out;
  std::visit(
      [&](const auto& m) {
        validate(m, Check{false});
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, TableChunk> || std::is_same_v<T, LinkFill>) out.reserve(40 + m.bytes.size());
        ByteWriter w(out);
        write(w, m);
      },
      message);
  return out;
}

std::vector<std::uint8_t> encode(const Message& message) {
  const MessageType type = message_type(message);
  std::vector<std::uint8_t> payload = encode_payload(message);
  // encode_payload enforced every field limit, so this holds; kept as a guard for future edits.
  if (payload.size() > *max_payload_bytes(static_cast<std::uint16_t>(type)))
    throw std::logic_error(std::string(to_string(type)) + ": payload above its documented maximum");
  std::vector<std::uint8_t> frame(kHeaderBytes + payload.size());
  std::copy(kMagic.begin(), kMagic.end(), frame.begin());
  frame[4] = static_cast<std::uint8_t>(kProtocolVersion >> 8);
  frame[5] = static_cast<std::uint8_t>(kProtocolVersion & 0xFF);
  const auto type_value = static_cast<std::uint16_t>(type);
  frame[6] = static_cast<std::uint8_t>(type_value >> 8);
  frame[7] = static_cast<std::uint8_t>(type_value & 0xFF);
  put_be32(&frame[8], static_cast<std::uint32_t>(payload.size()));
  put_be32(&frame[12], crc32c(payload));
  put_be32(&frame[16], crc32c(std::span<const std::uint8_t>(frame.data(), 16)));
  std::copy(payload.begin(), payload.end(), frame.begin() + static_cast<std::ptrdiff_t>(kHeaderBytes));
  return frame;
}

Message decode_payload(std::uint16_t type_value, std::span<const std::uint8_t> payload) {
  if (!max_payload_bytes(type_value))
    throw ProtocolError(ProtocolErrorCode::unknown_type,
                        "message type " + std::to_string(type_value) + " is not defined");
  const auto type = static_cast<MessageType>(type_value);
  ByteReader r(payload);
  Message m = read(type, r);
  r.expect_end(to_string(type));
  std::visit([](const auto& v) { validate(v, Check{true}); }, m);
  return m;
}

FrameHeader parse_header(std::span<const std::uint8_t, kHeaderBytes> h) {
  if (!std::equal(kMagic.begin(), kMagic.end(), h.begin())) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string got;
    for (int i = 0; i < 4; ++i) {
      got += kHex[h[i] >> 4];
      got += kHex[h[i] & 15];
    }
    throw ProtocolError(ProtocolErrorCode::bad_magic,
                        "frame header magic: 0x" + got + ", expected 0x5a4e5448 (\"ZNTH\")");
  }
  const auto be16 = [&](std::size_t o) { return static_cast<std::uint16_t>(h[o] << 8 | h[o + 1]); };
  const auto be32 = [&](std::size_t o) {
    return std::uint32_t{h[o]} << 24 | std::uint32_t{h[o + 1]} << 16 | std::uint32_t{h[o + 2]} << 8 | h[o + 3];
  };
  const std::uint16_t version = be16(4);
  if (version != kProtocolVersion)
    throw ProtocolError(
        ProtocolErrorCode::unsupported_version,
        "frame header version: " + std::to_string(version) + ", this build speaks " + std::to_string(kProtocolVersion));
  const std::uint32_t header_crc = crc32c(h.first<16>());
  if (header_crc != be32(16)) {
    char detail[96];
    std::snprintf(detail, sizeof detail, "frame header CRC-32C: computed 0x%08x, header says 0x%08x", header_crc,
                  be32(16));
    throw ProtocolError(ProtocolErrorCode::crc_mismatch, detail);
  }
  const std::uint16_t type_value = be16(6);
  const auto max = max_payload_bytes(type_value);
  if (!max)
    throw ProtocolError(ProtocolErrorCode::unknown_type, "frame header type: " + std::to_string(type_value) +
                                                             " is not a message type of version " +
                                                             std::to_string(kProtocolVersion));
  FrameHeader header;
  header.type = static_cast<MessageType>(type_value);
  header.payload_bytes = be32(8);
  header.payload_crc32c = be32(12);
  if (header.payload_bytes > *max)
    throw ProtocolError(ProtocolErrorCode::oversized,
                        "frame header payload length: " + std::to_string(header.payload_bytes) + " bytes exceeds the " +
                            std::to_string(*max) + "-byte limit of " + to_string(header.type));
  return header;
}

}  // namespace zenith::cluster
