// The cluster's datagrams (cluster/protocol/datagram.h): sealed with the
// session's key, opened only with it, every alteration refused.
#include <gtest/gtest.h>

#include <algorithm>

#include "cluster/protocol/datagram.h"
#include "cluster/protocol/handshake.h"
#include "tests/cluster/sample_messages.h"

namespace zenith::cluster {
namespace {

Digest key_of(std::uint8_t seed) {
  Digest d{};
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = static_cast<std::uint8_t>(seed + 7 * i);
  return d;
}

FrameState sample_frame() {
  for (const Message& m : sample_messages())
    if (const auto* f = std::get_if<FrameState>(&m)) return *f;
  throw std::logic_error("no sample FrameState");
}

TEST(Datagram, AScheduledFrameRoundTripsWithItsKey) {
  const Digest key = key_of(1);
  const std::vector<Message> messages = {FrameSchedule{42, 1'000'000'000, 16'666'667}, sample_frame()};
  const std::vector<std::uint8_t> d = seal_datagram(key, 7, messages);
  EXPECT_EQ(datagram_node_id(d), 7u);
  EXPECT_LE(d.size(), max_datagram_bytes());
  const auto opened = open_datagram(key, d);
  ASSERT_TRUE(std::holds_alternative<OpenedDatagram>(opened)) << std::get<DatagramRefusal>(opened).what;
  EXPECT_EQ(std::get<OpenedDatagram>(opened).node_id, 7u);
  EXPECT_EQ(std::get<OpenedDatagram>(opened).messages, messages);
}

TEST(Datagram, TheLargestFrameFitsAndStaysUnderTwoKibibytes) {
  for (const Message& m : max_size_messages())
    if (const auto* f = std::get_if<FrameState>(&m)) {
      const std::vector<Message> messages = {FrameSchedule{~0ull, ~0ull, kMaxFramePeriodNs}, *f};
      EXPECT_EQ(seal_datagram(key_of(2), 0xFFFFFFFFu, messages).size(), max_datagram_bytes());
    }
  EXPECT_LT(max_datagram_bytes(), 2048u);
}

TEST(Datagram, EveryAlteredByteAnotherKeyAndOtherMessagesAreRefused) {
  const Digest key = key_of(3);
  const std::vector<std::uint8_t> d = seal_datagram(key, 9, std::vector<Message>{ClockPing{123}});
  for (std::size_t i = 0; i < d.size(); ++i) {
    std::vector<std::uint8_t> altered = d;
    altered[i] ^= 0x01;
    EXPECT_TRUE(std::holds_alternative<DatagramRefusal>(open_datagram(key, altered))) << "byte " << i;
  }
  const auto wrong_key = open_datagram(key_of(4), d);
  ASSERT_TRUE(std::holds_alternative<DatagramRefusal>(wrong_key));
  EXPECT_NE(std::get<DatagramRefusal>(wrong_key).what.find("tag"), std::string::npos);
  EXPECT_TRUE(std::holds_alternative<DatagramRefusal>(open_datagram(key, std::span(d).first(10))));
  EXPECT_THROW(seal_datagram(key, 9, std::vector<Message>{Present{1}}), std::invalid_argument);
}

TEST(Datagram, TheKeyBelongsToOneSession) {
  const SharedSecret secret(std::vector<std::uint8_t>(32, 0x5a), "test");
  Nonce nm{}, nn{};
  nm[0] = 1;
  nn[0] = 2;
  const Digest k = datagram_key(secret, "dome", "a", nm, nn);
  EXPECT_NE(k, datagram_key(secret, "dome", "b", nm, nn));
  EXPECT_NE(k, datagram_key(secret, "dome2", "a", nm, nn));
  Nonce other = nn;
  other[31] = 9;
  EXPECT_NE(k, datagram_key(secret, "dome", "a", nm, other));
  // Both sides of a handshake derive the same key.
  NodeHandshake node(secret, "dome", "a");
  MasterHandshake master(secret, "dome");
  const Challenge challenge = master.on_hello(node.start());
  master.on_authenticate(node.on_challenge(challenge));
  node.on_welcome(master.welcome(1, 0, 250, 2000));
  EXPECT_EQ(node.datagram_key(), master.datagram_key());
}

}  // namespace
}  // namespace zenith::cluster
