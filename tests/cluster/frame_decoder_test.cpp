#include "cluster/protocol/frame_decoder.h"

#include <gtest/gtest.h>

#include "cluster/protocol/byte_io.h"
#include "test_support.h"
#include "tests/cluster/sample_messages.h"

namespace zenith::cluster {
namespace {

using Bytes = std::vector<std::uint8_t>;
using test::fix_crc;
using test::put_be16;
using test::put_be32;
using test::raw_frame;

/// Feeds `bytes` and expects next() to throw `code` with `needle` in its message.
void expect_error(const Bytes& bytes, ProtocolErrorCode code, const std::string& needle) {
  FrameDecoder decoder;
  decoder.feed(bytes);
  try {
    auto m = decoder.next();
    FAIL() << "no error; got " << (m ? "a message" : "nothing") << " (expected " << to_string(code) << ")";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
  EXPECT_TRUE(decoder.poisoned());
  EXPECT_THROW(decoder.next(), ProtocolError);  // stays poisoned
  decoder.feed(encode(Heartbeat{1}));           // and ignores further bytes
  EXPECT_THROW(decoder.next(), ProtocolError);
}

Bytes heartbeat_frame() { return encode(Heartbeat{42}); }

TEST(FrameDecoder, DecodesEverySample) {
  for (const Message& m : sample_messages()) {
    FrameDecoder decoder;
    decoder.feed(encode(m));
    auto got = decoder.next();
    ASSERT_TRUE(got.has_value());
    EXPECT_EQ(*got, m);
    EXPECT_FALSE(decoder.next().has_value());
    EXPECT_EQ(decoder.buffered_bytes(), 0u);
  }
}

TEST(FrameDecoder, FrameSplitIntoOneBytePiecesDecodes) {
  const Message m = sample_messages()[5];  // FrameState
  const Bytes frame = encode(m);
  FrameDecoder decoder;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    EXPECT_FALSE(decoder.next().has_value()) << "message before the last byte, at " << i;
    decoder.feed(std::span<const std::uint8_t>(&frame[i], 1));
  }
  auto got = decoder.next();
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(*got, m);
}

TEST(FrameDecoder, TwoFramesInOneFeedDecodeInOrder) {
  Bytes bytes = encode(Heartbeat{1});
  const Bytes second = encode(Present{2});
  bytes.insert(bytes.end(), second.begin(), second.end());
  FrameDecoder decoder;
  decoder.feed(bytes);
  EXPECT_EQ(decoder.queued_messages(), 2u);
  EXPECT_EQ(decoder.next(), Message{Heartbeat{1}});
  EXPECT_EQ(decoder.next(), Message{Present{2}});
  EXPECT_FALSE(decoder.next().has_value());
}

TEST(FrameDecoder, AllSamplesBackToBackInOddPieces) {
  Bytes stream;
  for (const Message& m : sample_messages()) {
    const Bytes f = encode(m);
    stream.insert(stream.end(), f.begin(), f.end());
  }
  FrameDecoder decoder;
  std::vector<Message> got;
  for (std::size_t at = 0; at < stream.size(); at += 37) {
    decoder.feed(std::span<const std::uint8_t>(stream).subspan(at, std::min<std::size_t>(37, stream.size() - at)));
    while (auto m = decoder.next()) got.push_back(std::move(*m));
  }
  EXPECT_EQ(got, sample_messages());
}

TEST(FrameDecoder, MessagesBeforeAnErrorAreDeliveredFirst) {
  Bytes bytes = encode(Heartbeat{1});
  bytes.insert(bytes.end(), {'X', 'X', 'X', 'X'});
  bytes.resize(bytes.size() + 16, 0);
  FrameDecoder decoder;
  decoder.feed(bytes);
  EXPECT_EQ(decoder.next(), Message{Heartbeat{1}});
  EXPECT_THROW(decoder.next(), ProtocolError);
}

TEST(FrameDecoder, BadMagic) {
  Bytes f = heartbeat_frame();
  f[0] = 'z';
  expect_error(f, ProtocolErrorCode::bad_magic, "frame header magic: 0x7a4e5448");
}

TEST(FrameDecoder, GarbageBytesAreRefusedAtTheHeader) {
  const std::string http = "GET / HTTP/1.1\r\nHost: x\r\n\r\n";
  expect_error(Bytes(http.begin(), http.end()), ProtocolErrorCode::bad_magic, "magic");
}

TEST(FrameDecoder, UnsupportedVersionInTheHeader) {
  Bytes f = heartbeat_frame();
  put_be16(f, 4, 1);  // the first release: no AtmosphereDefinition
  expect_error(f, ProtocolErrorCode::unsupported_version, "frame header version: 1");
  put_be16(f, 4, 2);  // no PreviewRequest and Thumbnail: a node of version 2 is refused, not half served
  expect_error(f, ProtocolErrorCode::unsupported_version, "frame header version: 2, this build speaks 5");
  put_be16(f, 4,
           3);  // no Hello.instance_id, FrameState without the fade and the sky, RenderDone without present counts
  expect_error(f, ProtocolErrorCode::unsupported_version, "frame header version: 3, this build speaks 5");
  put_be16(f, 4, 4);  // no scheduled frames, datagrams or clock exchange: its nodes would wait for Presents
  expect_error(f, ProtocolErrorCode::unsupported_version, "frame header version: 4, this build speaks 5");
}

TEST(FrameDecoder, UnsupportedVersionInHello) {
  Bytes f = encode(Hello{kProtocolVersion, "dome", "n1", {}});
  put_be16(f, kHeaderBytes, 7);
  fix_crc(f);
  expect_error(f, ProtocolErrorCode::unsupported_version, "Hello.protocol_version: 7");
}

TEST(FrameDecoder, UnknownType) {
  expect_error(raw_frame(999, Bytes(8, 0)), ProtocolErrorCode::unknown_type, "frame header type: 999");
}

TEST(FrameDecoder, OversizedLengthIsRejectedFromTheHeaderAloneWithoutBufferingThePayload) {
  Bytes f = encode(TableChunk{{}, 0, Bytes(16, 1)});
  put_be32(f, 8, static_cast<std::uint32_t>(*max_payload_bytes(33) + 1));
  test::fix_header_crc(f);
  f.resize(kHeaderBytes);  // only the header has arrived
  FrameDecoder decoder;
  decoder.feed(std::span<const std::uint8_t>(f).first(kHeaderBytes - 1));
  EXPECT_FALSE(decoder.next().has_value());  // 19 bytes: nothing to say yet
  decoder.feed(std::span<const std::uint8_t>(f).last(1));
  try {
    decoder.next();
    FAIL() << "no error";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), ProtocolErrorCode::oversized);
    EXPECT_NE(std::string(e.what()).find("payload length: 1048617 bytes exceeds the 1048616-byte limit of TableChunk"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(decoder.buffered_bytes(), 0u);
}

// The master once accepted 1 MiB TableChunk headers before
// the handshake (300 such peers: 22 -> 349 MB). Until the peer proved the
// secret its payloads are at most a handshake message's, checked at the header.
TEST(FrameDecoder, APayloadLimitBeforeTheHandshakeRefusesAChunkHeaderAndIsLiftedAfter) {
  EXPECT_EQ(max_handshake_payload_bytes(), 1026u) << "Goodbye's maximum, the largest of Hello, Authenticate, Goodbye";
  const Bytes chunk = encode(TableChunk{{}, 0, Bytes(4096, 7)});
  FrameDecoder limited;
  limited.limit_payload(max_handshake_payload_bytes(), "before the handshake");
  const Bytes hello = encode(Hello{kProtocolVersion, "dome", "n1", {}, PeerRole::node, 42});
  limited.feed(hello);
  EXPECT_TRUE(limited.next().has_value()) << "a Hello passes";
  limited.feed(std::span<const std::uint8_t>(chunk).first(kHeaderBytes));
  try {
    limited.next();
    FAIL() << "no error";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), ProtocolErrorCode::oversized);
    EXPECT_NE(std::string(e.what()).find("4136 bytes of a TableChunk exceeds the 1026-byte limit before the handshake"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(limited.buffered_bytes(), 0u) << "nothing of the payload is held";
  FrameDecoder lifted;
  lifted.limit_payload(max_handshake_payload_bytes(), "before the handshake");
  lifted.lift_payload_limit();  // the peer authenticated: each type's own maximum again
  lifted.feed(chunk);
  EXPECT_TRUE(lifted.next().has_value());
}

TEST(FrameDecoder, PerTypeLimitAppliesNotJustTheGlobalOne) {
  Bytes f = raw_frame(static_cast<std::uint16_t>(MessageType::heartbeat), Bytes(9, 0));
  expect_error(f, ProtocolErrorCode::oversized, "exceeds the 8-byte limit of Heartbeat");
  Bytes huge = heartbeat_frame();
  put_be32(huge, 8, 0xFFFFFFFFu);
  test::fix_header_crc(huge);
  huge.resize(kHeaderBytes);
  expect_error(huge, ProtocolErrorCode::oversized, "4294967295 bytes");
}

TEST(FrameDecoder, CrcMismatch) {
  Bytes f = encode(Goodbye{"bye"});
  f.back() ^= 0x01;
  expect_error(f, ProtocolErrorCode::crc_mismatch, "Goodbye payload CRC-32C");
}

TEST(FrameDecoder, HeaderCrcMismatch) {
  Bytes f = heartbeat_frame();
  f[11] ^= 0x04;  // a corrupted length is caught by the header's own CRC before it is trusted
  expect_error(f, ProtocolErrorCode::crc_mismatch, "frame header CRC-32C");
}

TEST(FrameDecoder, MalformedPayloadTruncatedField) {
  // Hello whose payload stops inside the nonce (length field and CRC consistent).
  Bytes f = encode(Hello{kProtocolVersion, "dome", "n1", {}});
  f.resize(f.size() - 8 - 1 - 5);  // the instance id, the role and 5 bytes of the nonce
  put_be32(f, 8, static_cast<std::uint32_t>(f.size() - kHeaderBytes));
  fix_crc(f);
  expect_error(f, ProtocolErrorCode::malformed_payload, "Hello.node_nonce: truncated");
}

TEST(FrameDecoder, MalformedPayloadCountAboveItsLimit) {
  // A valid FrameState with its atmosphere count overwritten to 9.
  FrameState fs;
  fs.sun_irradiance_W_m2_nm = {1.0};
  Bytes f = encode(fs);
  const std::size_t count_at = kHeaderBytes + 8 + 8 + 24 + 32 + 8 + 24 + 8 + 1 + 8;
  ASSERT_EQ(f[count_at], 0);
  f[count_at] = 9;
  fix_crc(f);
  expect_error(f, ProtocolErrorCode::malformed_payload, "FrameState.atmospheres count: 9, at most 8");
}

TEST(FrameDecoder, MalformedPayloadOutOfRangeValue) {
  Bytes f = encode(FrameState{});
  put_be32(f, f.size() - 4 - 32 - 49,
           0x80000000u);  // unknown render flag (before the fade's 4 f64 and the sky's 49 bytes)
  fix_crc(f);
  expect_error(f, ProtocolErrorCode::malformed_payload, "FrameState.render_flags: unknown bits");
  Bytes k = encode(FrameState{});
  k[k.size() - 49] = 2;  // an unknown sky flag
  fix_crc(k);
  expect_error(k, ProtocolErrorCode::malformed_payload, "FrameState.sky.flags: unknown bits");

  Bytes h = encode(FrameState{});
  put_be32(h, h.size() - 49 - 32, 0x3FF80000u);  // fade level 1.5 (0x3FF8… as f64), before the sky fields
  fix_crc(h);
  expect_error(h, ProtocolErrorCode::malformed_payload, "FrameState.fade_level: must be in [0, 1]");

  Bytes g = encode(TableAnnounce{{}, 10000, 4096, 3, {}});
  put_be32(g, kHeaderBytes + 32 + 8 + 4, 4);  // chunk_count 4 ≠ ceil(10000 / 4096)
  fix_crc(g);
  expect_error(g, ProtocolErrorCode::malformed_payload, "TableAnnounce.chunk_count: 4");
}

TEST(FrameDecoder, TrailingBytes) {
  Bytes payload = encode_payload(Goodbye{"ab"});
  payload.push_back('!');
  expect_error(raw_frame(static_cast<std::uint16_t>(MessageType::goodbye), payload), ProtocolErrorCode::trailing_bytes,
               "Goodbye: 1 trailing byte(s)");
}

TEST(FrameDecoder, BufferNeverExceedsHeaderPlusTheTypesMaximum) {
  const Bytes f = encode(max_size_messages()[9]);  // the 1 MiB TableChunk
  FrameDecoder decoder;
  for (std::size_t at = 0; at < f.size(); at += 65536) {
    decoder.feed(std::span<const std::uint8_t>(f).subspan(at, std::min<std::size_t>(65536, f.size() - at)));
    EXPECT_LE(decoder.buffered_bytes(), kHeaderBytes + *max_payload_bytes(33));
  }
  EXPECT_EQ(decoder.buffered_bytes(), 0u);
  ASSERT_TRUE(decoder.next().has_value());
  EXPECT_EQ(FrameDecoder::max_buffered_bytes(), kHeaderBytes + (1u << 20) + 40);
}

}  // namespace
}  // namespace zenith::cluster
