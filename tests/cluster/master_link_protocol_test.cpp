// The node's side of its link to the master without sockets
// (cluster/node/master_link_protocol.h; docs/protocol.md, "Handshake";
// docs/cluster.md, "Join, rejoin and failures").
#include "cluster/node/master_link_protocol.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace zenith::cluster {
namespace {

using Meaning = MasterLinkProtocol::Meaning;
using Tick = MasterLinkProtocol::Tick;
using std::chrono::milliseconds;

const MasterLinkProtocol::Clock::time_point t0 = MasterLinkProtocol::Clock::now();

SharedSecret secret(char fill = 's') { return SharedSecret(std::vector<std::uint8_t>(32, std::uint8_t(fill)), "test"); }

/// A node (heartbeat 250 ms in its configuration, connect timeout 20 s).
MasterLinkProtocol node_link() { return MasterLinkProtocol(secret(), "dome", "left", 250, 20000); }

/// The handshake up to the master's Welcome, the master's side played by MasterHandshake.
Welcome handshake(MasterLinkProtocol& link, MasterHandshake& master, std::uint32_t heartbeat_ms = 500) {
  const Hello hello = link.start();
  EXPECT_EQ(hello.node_name, "left");
  EXPECT_EQ(hello.cluster_name, "dome");
  const MasterLinkProtocol::Step answer = link.on_message(master.on_hello(hello));
  EXPECT_EQ(answer.meaning, Meaning::reply);
  EXPECT_TRUE(answer.reply && std::holds_alternative<Authenticate>(*answer.reply));
  master.on_authenticate(std::get<Authenticate>(*answer.reply));  // throws when the node's proof is wrong
  return master.welcome(7, 42, heartbeat_ms, 1000);
}

TEST(MasterLinkProtocol, TheHandshakeWithTheMasterEndsInWelcome) {
  MasterLinkProtocol link = node_link();
  MasterHandshake master(secret(), "dome");
  const Welcome welcome = handshake(link, master);
  EXPECT_FALSE(link.welcomed());
  EXPECT_EQ(link.on_message(welcome).meaning, Meaning::welcomed);
  EXPECT_TRUE(link.welcomed());
  EXPECT_EQ(link.heartbeat_ms(), 500u) << "the master's interval from Welcome on";
}

TEST(MasterLinkProtocol, AWelcomeWithoutTheMastersProofIsRefused) {
  MasterLinkProtocol link = node_link();
  MasterHandshake master(secret(), "dome");
  Welcome welcome = handshake(link, master);
  welcome.master_mac[0] ^= 1;
  EXPECT_THROW(link.on_message(welcome), HandshakeError);
  EXPECT_FALSE(link.welcomed());
}

TEST(MasterLinkProtocol, BeforeWelcomeOnlyTheHandshakesMessagesAreAccepted) {
  MasterLinkProtocol link = node_link();
  (void)link.start();
  for (const Message& m : std::vector<Message>{FrameState{}, Present{}, Heartbeat{}, TableChunk{}}) {
    try {
      (void)link.on_message(m);
      ADD_FAILURE() << to_string(message_type(m)) << " accepted before Welcome";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), std::string(to_string(message_type(m))) + " from the master before Welcome");
    }
  }
}

TEST(MasterLinkProtocol, RejectOrGoodbyeEndTheLink) {
  MasterLinkProtocol link = node_link();
  (void)link.start();
  EXPECT_EQ(link.on_message(Reject{RejectReason::duplicate_node, "taken"}).meaning, Meaning::rejected);
  EXPECT_EQ(link.on_message(Goodbye{"shutting down"}).meaning, Meaning::goodbye);
  EXPECT_FALSE(link.welcomed()) << "a Goodbye before Welcome is a refusal";
}

TEST(MasterLinkProtocol, AfterWelcomeTheMastersMessagesAreTheNodesWork) {
  MasterLinkProtocol link = node_link();
  MasterHandshake master(secret(), "dome");
  (void)link.on_message(handshake(link, master));
  for (const Message& m : std::vector<Message>{FrameState{}, Present{}, TableAnnounce{}, TableChunk{},
                                               AtmosphereDefinition{}, Challenge{}})
    EXPECT_EQ(link.on_message(m).meaning, Meaning::work) << to_string(message_type(m));
  EXPECT_EQ(link.on_message(Heartbeat{}).meaning, Meaning::heartbeat);
  EXPECT_EQ(link.on_message(Goodbye{"show over"}).meaning, Meaning::goodbye);
}

TEST(MasterLinkProtocol, BeforeWelcomeTheConnectTimeoutAppliesAndNoHeartbeatIsSent) {
  MasterLinkProtocol link = node_link();
  (void)link.start();
  EXPECT_DOUBLE_EQ(link.silence_limit_ms(), 20000.0);
  EXPECT_EQ(link.tick(t0, t0 + milliseconds(20000)), Tick::wait) << "the master may still be preparing tables";
  EXPECT_EQ(link.tick(t0, t0 + milliseconds(20001)), Tick::master_gone);
  EXPECT_EQ(link.heartbeat_ms(), 250u) << "the configuration's interval until Welcome";
}

TEST(MasterLinkProtocol, AfterWelcomeAHeartbeatPerTickUntilTheMasterFallsSilent) {
  MasterLinkProtocol link = node_link();
  MasterHandshake master(secret(), "dome");
  (void)link.on_message(handshake(link, master, 5000));
  EXPECT_DOUBLE_EQ(link.silence_limit_ms(), 15000.0) << "3 heartbeats of the master's, at least 10 s";
  EXPECT_EQ(link.tick(t0, t0 + milliseconds(15000)), Tick::send_heartbeat);
  EXPECT_EQ(link.tick(t0, t0 + milliseconds(15001)), Tick::master_gone);
  EXPECT_EQ(link.tick(t0 + milliseconds(10000), t0 + milliseconds(20000)), Tick::send_heartbeat)
      << "what counts is the last bytes received";
}

}  // namespace
}  // namespace zenith::cluster
