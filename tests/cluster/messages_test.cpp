#include "cluster/protocol/messages.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

#include "cluster/protocol/crc32c.h"
#include "test_support.h"
#include "tests/cluster/sample_messages.h"

namespace zenith::cluster {
namespace {

using Bytes = std::vector<std::uint8_t>;

FrameState known_frame_state() {
  FrameState f;
  f.frame = 0x0102030405060708ull;
  f.show_time_s = 1.0;
  f.camera_position_m = {2.0, -2.0, 0.5};
  f.camera_orientation = {1, 0, 0, 0};
  f.exposure = 10.0;
  f.sun_direction = {0, 0, 1};
  f.sun_angular_radius_rad = 0.25;
  f.sun_irradiance_W_m2_nm = {1.5};
  f.atmospheres.push_back({"Mars", Digest{}, 7});
  f.render_flags = kRenderSunDisc | kRenderEclipses;
  f.fade = {0.5, glm::dvec3(0.0, 1.0, 0.0)};
  return f;
}

TEST(Messages, HeaderBytesOfAKnownFrameStateAreBigEndian) {
  const Bytes frame = encode(known_frame_state());
  const std::size_t payload_bytes =
      8 + 8 + 24 + 32 + 8 + 24 + 8 + 1 + 8 + 1 + (2 + 4 + 32 + 8) + 4 + 8 + 24 + (1 + 8 + 8 + 32);
  ASSERT_EQ(frame.size(), kHeaderBytes + payload_bytes);
  const Bytes payload(frame.begin() + kHeaderBytes, frame.end());
  const std::uint32_t crc = crc32c(payload);
  const Bytes expected_header = {'Z', 'N', 'T', 'H',                                          // magic
                                 0x00, 0x05,                                                  // version 5
                                 0x00, 0x10,                                                  // type 16 = FrameState
                                 0x00, 0x00, 0x00, static_cast<std::uint8_t>(payload_bytes),  // length
                                 // payload CRC-32C
                                 static_cast<std::uint8_t>(crc >> 24), static_cast<std::uint8_t>(crc >> 16),
                                 static_cast<std::uint8_t>(crc >> 8), static_cast<std::uint8_t>(crc)};
  ASSERT_EQ(expected_header.size(), 16u);
  EXPECT_EQ(Bytes(frame.begin(), frame.begin() + 16), expected_header);
  // Bytes 16..19: CRC-32C of bytes 0..15, big-endian.
  const std::uint32_t header_crc = crc32c(std::span<const std::uint8_t>(frame).first(16));
  EXPECT_EQ(Bytes(frame.begin() + 16, frame.begin() + 20),
            (Bytes{static_cast<std::uint8_t>(header_crc >> 24), static_cast<std::uint8_t>(header_crc >> 16),
                   static_cast<std::uint8_t>(header_crc >> 8), static_cast<std::uint8_t>(header_crc)}));
  // The payload starts with the frame number, then show_time_s = 1.0 (0x3FF0…), position x = 2.0 (0x4000…).
  const Bytes expected_start = {1,    2, 3, 4, 5, 6, 7, 8, 0x3F, 0xF0, 0, 0, 0, 0, 0, 0,
                                0x40, 0, 0, 0, 0, 0, 0, 0, 0xC0, 0,    0, 0, 0, 0, 0, 0};
  EXPECT_EQ(Bytes(payload.begin(), payload.begin() + 32), expected_start);
  // Orientation w = 1.0 comes first (offset 40), then x, y, z.
  EXPECT_EQ(payload[40], 0x3F);
  EXPECT_EQ(payload[41], 0xF0);
  // Then the flags: sun disc | eclipses = 9; the fade: level 0.5 (0x3FE0…), colour 0, 1, 0; the sky
  // fields close the payload (49 bytes, no time: all zero).
  EXPECT_EQ(Bytes(payload.end() - 49 - 36, payload.end() - 49 - 32), (Bytes{0, 0, 0, 9}));
  EXPECT_EQ(Bytes(payload.end() - 49 - 32, payload.end() - 49 - 24), (Bytes{0x3F, 0xE0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(Bytes(payload.end() - 49 - 16, payload.end() - 49 - 8), (Bytes{0x3F, 0xF0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(Bytes(payload.end() - 49, payload.end()), Bytes(49, 0));
  // Atmosphere entry: u16 length 4, "Mars".
  const std::size_t atmosphere_at = 8 + 8 + 24 + 32 + 8 + 24 + 8 + 1 + 8 + 1;
  EXPECT_EQ(Bytes(payload.begin() + atmosphere_at, payload.begin() + atmosphere_at + 6),
            (Bytes{0, 4, 'M', 'a', 'r', 's'}));
}

TEST(Messages, EverySampleRoundTrips) {
  for (const Message& m : sample_messages()) {
    const Bytes frame = encode(m);
    const auto header = parse_header(std::span<const std::uint8_t, kHeaderBytes>(frame.data(), kHeaderBytes));
    EXPECT_EQ(header.type, message_type(m));
    EXPECT_EQ(header.payload_bytes, frame.size() - kHeaderBytes);
    const Message back = decode_payload(static_cast<std::uint16_t>(header.type),
                                        std::span<const std::uint8_t>(frame).subspan(kHeaderBytes));
    EXPECT_EQ(back, m) << to_string(message_type(m));
    EXPECT_EQ(encode(back), frame);
  }
}

TEST(Messages, MaximumSizeMessagesRoundTripAndReachTheirDocumentedLimitExactly) {
  const auto messages = max_size_messages();
  EXPECT_EQ(messages.size(), std::variant_size_v<Message>);
  for (const Message& m : messages) {
    const Bytes payload = encode_payload(m);
    const auto type = static_cast<std::uint16_t>(message_type(m));
    EXPECT_EQ(payload.size(), *max_payload_bytes(type)) << to_string(message_type(m));
    EXPECT_EQ(decode_payload(type, payload), m) << to_string(message_type(m));
  }
}

TEST(Messages, DocumentedMaximumPayloads) {
  // Each payload at its limits, field by field (messages.cpp): an integer's
  // bytes, a string's 2-byte length and kMaxNameBytes (64) or kMaxReasonBytes
  // (1024), a digest's 32 bytes.
  const std::pair<MessageType, std::size_t> expected[] = {
      // version, cluster name, node name, nonce, role, instance id
      {MessageType::hello, 2u + 66u + 66u + 32u + 1u + 8u},
      {MessageType::challenge, 32u},     // nonce
      {MessageType::authenticate, 32u},  // MAC
      // node id, MAC, current frame, heartbeat interval, barrier timeout, master's clock
      {MessageType::welcome, 4u + 32u + 8u + 4u + 4u + 8u},
      {MessageType::reject, 2u + 1026u},  // reason, text
      // frame, show time, camera position and orientation, exposure, sun direction and radius; 64 irradiance
      // samples; 8 atmospheres (body name, table hash, from frame); flags; fade level and colour; sky clock
      // (has time, two-part Julian date, catalogue digest)
      {MessageType::frame_state, 8u + 8u + 3u * 8u + 4u * 8u + 8u + 3u * 8u + 8u + (1u + 64u * 8u) +
                                     (1u + 8u * (66u + 32u + 8u)) + 4u + 8u + 3u * 8u + 1u + 2u * 8u + 32u},
      {MessageType::render_done, 6u * 8u},  // frame, render ms, presents, late presents, present ms, missed frames
      {MessageType::present, 8u},           // frame
      // hash, total bytes, chunk bytes, chunk count, content digest
      {MessageType::table_announce, 32u + 8u + 4u + 4u + 32u},
      {MessageType::table_chunk, 32u + 4u + 4u + (1u << 20)},  // hash, index, length, 1 MiB
      {MessageType::table_ready, 32u},                         // hash
      {MessageType::heartbeat, 8u},                            // frame
      {MessageType::goodbye, 1026u},                           // text
      // body name, table hash, length, 256 KiB of JSON
      {MessageType::atmosphere_definition, 66u + 32u + 4u + 262144u},
      {MessageType::preview_request, 8u + 2u},  // frame, edge
      // frame, output name, width, height, length, 64 × 64 RGB bytes
      {MessageType::thumbnail, 8u + 66u + 2u + 2u + 4u + 64u * 64u * 3u},
      {MessageType::frame_schedule, 3u * 8u},          // frame, moment on the master's clock, period
      {MessageType::clock_ping, 8u},                   // the node's clock
      {MessageType::clock_pong, 3u * 8u},              // the ping's stamp, the master's clock at arrival and answer
      {MessageType::link_check, 4u + 4u + 8u},         // duration, ping interval, fill bytes
      {MessageType::link_fill, 4u + 4u + (1u << 20)},  // index, length, 1 MiB
      // pings, pongs, first and last ping, four round trips, node's clock, master's, wall clock,
      // uncertainty, drift, steps, fill bytes, timed bytes, fill time
      {MessageType::link_report, 4u + 4u + 2u * 8u + 4u * 8u + 3u * 8u + 8u + 8u + 4u + 3u * 8u}};
  for (const auto& [type, bytes] : expected)
    EXPECT_EQ(max_payload_bytes(static_cast<std::uint16_t>(type)), bytes) << to_string(type);
  EXPECT_FALSE(max_payload_bytes(0).has_value());
  EXPECT_FALSE(max_payload_bytes(6).has_value());
  EXPECT_FALSE(max_payload_bytes(0xFFFF).has_value());
}

TEST(Messages, HelloEndsWithTheRoleThenTheInstanceId) {
  Hello hello{kProtocolVersion, "dome", "standby@h:1", {}, PeerRole::standby, 0x0102030405060708u};
  Bytes payload = encode_payload(hello);
  EXPECT_EQ(Bytes(payload.end() - 9, payload.end()), (Bytes{1, 1, 2, 3, 4, 5, 6, 7, 8}))
      << "the role, then the instance id big-endian (version 4)";
  EXPECT_EQ(decode_payload(static_cast<std::uint16_t>(MessageType::hello), payload), Message{hello});
  EXPECT_EQ(*(encode_payload(Hello{kProtocolVersion, "dome", "a", {}}).end() - 9), 0) << "a node by default";
  *(payload.end() - 9) = 2;
  try {
    decode_payload(static_cast<std::uint16_t>(MessageType::hello), payload);
    FAIL() << "role 2 must be refused";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), ProtocolErrorCode::malformed_payload);
    EXPECT_NE(std::string(e.what()).find("Hello.role: 2, must be 0 (node) or 1 (standby)"), std::string::npos)
        << e.what();
  }
  hello.role = static_cast<PeerRole>(9);
  EXPECT_THROW(encode(hello), std::invalid_argument);
}

TEST(Messages, EncoderRefusesWhatTheDecoderWouldRefuse) {
  Hello hello{kProtocolVersion, "dome", std::string(kMaxNameBytes + 1, 'x'), {}};
  EXPECT_THROW(encode(hello), std::length_error);
  hello.node_name = "";
  EXPECT_THROW(encode(hello), std::invalid_argument);

  FrameState f = known_frame_state();
  f.exposure = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(encode(f), std::invalid_argument);
  f = known_frame_state();
  f.camera_orientation = {2, 0, 0, 0};
  EXPECT_THROW(encode(f), std::invalid_argument);
  f = known_frame_state();
  f.render_flags = 1u << 31;
  EXPECT_THROW(encode(f), std::invalid_argument);
  f = known_frame_state();
  f.atmospheres.resize(kMaxAtmospheres + 1, f.atmospheres[0]);
  EXPECT_THROW(encode(f), std::invalid_argument);
  f = known_frame_state();
  f.sun_irradiance_W_m2_nm.assign(kMaxWavelengths + 1, 1.0);
  EXPECT_THROW(encode(f), std::invalid_argument);

  EXPECT_THROW(encode(TableAnnounce{{}, 10000, 4096, 2, {}}), std::invalid_argument);  // needs 3 chunks
  EXPECT_THROW(encode(TableAnnounce{{}, kMaxTableTotalBytes + 1, 1 << 20, 2049, {}}), std::invalid_argument);
  EXPECT_THROW(encode(TableChunk{{}, 0, {}}), std::invalid_argument);
  EXPECT_THROW(encode(TableChunk{{}, 0, std::vector<std::uint8_t>(kMaxTableChunkBytes + 1)}), std::invalid_argument);
  EXPECT_THROW(encode(RenderDone{1, -1.0}), std::invalid_argument);
  EXPECT_THROW(encode(RenderDone{1, 1.0, 3, 4, 0.0}), std::invalid_argument);  // more late presents than presents
  EXPECT_THROW(encode(RenderDone{1, 1.0, 3, 1, -2.0}), std::invalid_argument);
  f = known_frame_state();
  f.fade.level = 1.5;
  EXPECT_THROW(encode(f), std::invalid_argument);
  f = known_frame_state();
  f.fade.colour.z = -0.1;
  EXPECT_THROW(encode(f), std::invalid_argument);

  EXPECT_THROW(encode(AtmosphereDefinition{"Earth", {}, "[1, 2]"}), std::invalid_argument);  // not an object
  EXPECT_THROW(encode(AtmosphereDefinition{"", {}, "{}"}), std::invalid_argument);
  EXPECT_THROW(encode(AtmosphereDefinition{"Earth", {}, "{" + std::string(kMaxDefinitionBytes, ' ') + "}"}),
               std::length_error);

  EXPECT_THROW(encode(PreviewRequest{1, 0}), std::invalid_argument);
  EXPECT_THROW(encode(PreviewRequest{1, kMaxThumbnailEdgePx + 1}), std::invalid_argument);
  EXPECT_THROW(encode(Thumbnail{1, "", 1, 1, {0, 0, 0}}), std::invalid_argument);
  EXPECT_THROW(encode(Thumbnail{1, "a", 0, 1, {}}), std::invalid_argument);
  EXPECT_THROW(encode(Thumbnail{1, "a", 65, 1, std::vector<std::uint8_t>(65 * 3)}), std::invalid_argument);
  EXPECT_THROW(encode(Thumbnail{1, "a", 2, 2, std::vector<std::uint8_t>(11)}), std::invalid_argument);
}

TEST(Messages, PreviewRequestAndThumbnailLayout) {
  EXPECT_EQ(encode_payload(PreviewRequest{0x0102030405060708ull, 64}), (Bytes{1, 2, 3, 4, 5, 6, 7, 8, 0, 64}));
  // u64 frame, u16 name length, name, u16 width, u16 height, u32 byte count, bytes.
  const Thumbnail t{9, "q", 2, 1, {10, 11, 12, 13, 14, 15}};
  const Bytes payload = encode_payload(t);
  const Bytes expected = {0, 0, 0, 0, 0, 0, 0, 9, 0, 1, 'q', 0, 2, 0, 1, 0, 0, 0, 6, 10, 11, 12, 13, 14, 15};
  EXPECT_EQ(payload, expected);
  EXPECT_EQ(std::get<Thumbnail>(decode_payload(static_cast<std::uint16_t>(MessageType::thumbnail), payload)), t);
  // Bytes that do not match the size are refused, as is a count beyond 64 × 64 × 3.
  Bytes short_count = payload;
  short_count[18] = 3;
  short_count.resize(short_count.size() - 3);
  EXPECT_THROW(decode_payload(static_cast<std::uint16_t>(MessageType::thumbnail), short_count), ProtocolError);
  Bytes huge = payload;
  huge[16] = 0x01;  // 65542 bytes
  EXPECT_THROW(decode_payload(static_cast<std::uint16_t>(MessageType::thumbnail), huge), ProtocolError);
  Bytes zero_edge = encode_payload(PreviewRequest{1, 1});
  zero_edge[9] = 0;
  EXPECT_THROW(decode_payload(static_cast<std::uint16_t>(MessageType::preview_request), zero_edge), ProtocolError);
}

TEST(Messages, AtmosphereDefinitionLayout) {
  // u16 name length, name, 32-byte hash, u32 text length, text: all big-endian.
  const AtmosphereDefinition d{"Io", Digest{}, "{}"};
  const Bytes payload = encode_payload(d);
  Bytes expected = {0, 2, 'I', 'o'};
  expected.insert(expected.end(), 32, 0);  // the hash
  expected.insert(expected.end(), {0, 0, 0, 2, '{', '}'});
  EXPECT_EQ(payload, expected);
  // A length beyond the limit is refused before the text is read.
  Bytes oversized = payload;
  oversized[36] = 0x00, oversized[37] = 0x04, oversized[38] = 0x00, oversized[39] = 0x01;  // 262145 bytes
  EXPECT_THROW(decode_payload(static_cast<std::uint16_t>(MessageType::atmosphere_definition), oversized),
               ProtocolError);
}

TEST(Messages, DigestHex) {
  const std::string hex = "00ff10ab" + std::string(56, 'c');
  const Digest d = digest_from_hex(hex);
  EXPECT_EQ(d[0], 0x00);
  EXPECT_EQ(d[1], 0xFF);
  EXPECT_EQ(d[3], 0xAB);
  EXPECT_EQ(to_hex(d), hex);
  EXPECT_EQ(digest_from_hex("00FF10AB" + std::string(56, 'C')), d);
  EXPECT_THROW(digest_from_hex("abc"), std::invalid_argument);
  EXPECT_THROW(digest_from_hex(std::string(63, '0') + "g"), std::invalid_argument);
}

TEST(Messages, TypeNames) {
  EXPECT_STREQ(to_string(MessageType::frame_state), "FrameState");
  EXPECT_STREQ(to_string(static_cast<MessageType>(999)), "unknown");
  EXPECT_EQ(message_type(Message{Goodbye{}}), MessageType::goodbye);
}

}  // namespace
}  // namespace zenith::cluster
