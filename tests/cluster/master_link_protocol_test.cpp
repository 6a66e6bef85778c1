// The node's side of its link to the master without sockets
// (cluster/link/master_link_protocol.h; docs/protocol.md, "Handshake";
// docs/cluster.md, "Join, rejoin and failures").
#include "cluster/link/master_link_protocol.h"

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

/// Connect timeout 20 s, reconnect time 30 s, waits from 100 ms doubling to 2 s, ±20 %.
ReconnectRules rules(std::uint32_t reconnect_ms = 30000) {
  ReconnectRules r;
  r.connect_timeout_ms = 20000;
  r.reconnect_ms = reconnect_ms;
  r.first_retry_ms = 100;
  r.max_retry_ms = 2000;
  r.jitter = 0.2;
  return r;
}

/// A node (heartbeat 250 ms in its configuration), begun at t0.
MasterLinkProtocol node_link(ReconnectRules r = rules(), const std::string& name = "left") {
  MasterLinkProtocol link(secret(), "dome", name, 250, r);
  link.begin(t0);
  return link;
}

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
  EXPECT_EQ(link.deadline(), t0 + milliseconds(20000));
  EXPECT_EQ(link.tick(t0, t0 + milliseconds(20000)), Tick::wait) << "the master may still be preparing tables";
  EXPECT_EQ(link.tick(t0, t0 + milliseconds(20001)), Tick::silent);
  EXPECT_EQ(link.heartbeat_ms(), 250u) << "the configuration's interval until Welcome";
  EXPECT_TRUE(link.connection_failed(t0 + milliseconds(20001)).give_up) << "no Welcome within the connect timeout";
}

TEST(MasterLinkProtocol, AfterWelcomeAHeartbeatPerTickUntilTheMasterFallsSilent) {
  MasterLinkProtocol link = node_link();
  MasterHandshake master(secret(), "dome");
  (void)link.on_message(handshake(link, master, 5000));
  EXPECT_DOUBLE_EQ(link.silence_limit_ms(), 15000.0) << "3 heartbeats of the master's, at least 10 s";
  EXPECT_EQ(link.tick(t0, t0 + milliseconds(15000)), Tick::send_heartbeat);
  EXPECT_EQ(link.tick(t0, t0 + milliseconds(15001)), Tick::silent);
  EXPECT_EQ(link.tick(t0 + milliseconds(10000), t0 + milliseconds(20000)), Tick::send_heartbeat)
      << "what counts is the last bytes received";
}

// ---- reconnection ----------------------------------------------------------

/// The waits of `n` failed attempts in a row starting at `now`, each made when the last wait is over.
std::vector<std::int64_t> waits(MasterLinkProtocol& link, MasterLinkProtocol::Clock::time_point now, int n) {
  std::vector<std::int64_t> out;
  for (int i = 0; i < n; ++i) {
    const MasterLinkProtocol::Retry r = link.connection_failed(now);
    if (r.give_up) break;
    out.push_back(r.delay.count());
    now += r.delay;
  }
  return out;
}

TEST(MasterLinkProtocol, TheWaitDoublesFrom100MsUpTo2SWithJitterOfAFifthEitherWay) {
  const ReconnectRules r = rules();
  const std::vector<std::int64_t> nominal = {100, 200, 400, 800, 1600, 2000, 2000, 2000};
  for (std::uint32_t failed = 1; failed <= nominal.size(); ++failed)
    EXPECT_EQ(MasterLinkProtocol::backoff(r, failed).count(), nominal[failed - 1]) << failed;
  EXPECT_EQ(MasterLinkProtocol::backoff(r, 1000).count(), 2000) << "no overflow";

  MasterLinkProtocol link = node_link();  // the first connection: refused again and again
  const std::vector<std::int64_t> w = waits(link, t0, 8);
  ASSERT_EQ(w.size(), 8u);
  for (std::size_t i = 0; i < w.size(); ++i) {
    EXPECT_GE(w[i], static_cast<std::int64_t>(0.8 * nominal[i]) - 1) << "attempt " << i + 1;
    EXPECT_LE(w[i], static_cast<std::int64_t>(1.2 * nominal[i])) << "attempt " << i + 1;
  }
  EXPECT_EQ(link.failed_attempts(), 8u);
  // The jitter is the node's own: the same for the same name, spread across names.
  MasterLinkProtocol again = node_link();
  EXPECT_EQ(waits(again, t0, 8), w);
  int differing = 0;
  for (const char* name : {"a", "b", "c", "d", "e", "f"}) {
    MasterLinkProtocol other = node_link(rules(), name);
    differing += waits(other, t0, 8) != w;
  }
  EXPECT_GE(differing, 5) << "nodes of a restarted master do not knock in step";
}

TEST(MasterLinkProtocol, ALostConnectionIsRetriedAtOnceThenWithBackoffUntilTheReconnectTime) {
  MasterLinkProtocol link = node_link();
  MasterHandshake master(secret(), "dome");
  (void)link.on_message(handshake(link, master));
  ASSERT_TRUE(link.welcomed());
  const auto lost = t0 + std::chrono::seconds(100);
  const MasterLinkProtocol::Retry first = link.connection_failed(lost);
  EXPECT_FALSE(first.give_up);
  EXPECT_EQ(first.delay.count(), 0) << "the first attempt after a loss is immediate";
  EXPECT_TRUE(link.reconnecting());
  EXPECT_FALSE(link.welcomed());
  EXPECT_EQ(link.deadline(), lost + milliseconds(30000)) << "the reconnect time counts from the loss";
  EXPECT_EQ(link.tick(lost, lost + milliseconds(29999)), Tick::wait) << "a master may welcome late (tables)";
  EXPECT_EQ(link.tick(lost, lost + milliseconds(30001)), Tick::silent);

  // Refused until the reconnect time runs out: the waits never pass the deadline.
  auto now = lost;
  std::int64_t total = 0;
  int attempts = 1;
  for (;;) {
    const MasterLinkProtocol::Retry r = link.connection_failed(now);
    if (r.give_up) break;
    ++attempts;
    total += r.delay.count();
    now += r.delay;
    ASSERT_LE(now, link.deadline());
    ASSERT_LT(attempts, 100);
  }
  EXPECT_EQ(now, lost + milliseconds(30000)) << "the last attempt is made at the deadline";
  EXPECT_EQ(total, 30000);
  // 0, then ~0.1 + 0.2 + 0.4 + 0.8 + 1.6 s = 3.1 s, then every ~2 s: about 15 attempts in 30 s.
  EXPECT_GE(attempts, 13);
  EXPECT_LE(attempts, 20);
}

TEST(MasterLinkProtocol, AWelcomeResetsTheAttemptsAndTheNextLossGetsTheWholeReconnectTime) {
  MasterLinkProtocol link = node_link();
  MasterHandshake master(secret(), "dome");
  (void)link.on_message(handshake(link, master));
  auto now = t0 + std::chrono::seconds(10);
  (void)link.connection_failed(now);  // lost
  for (int i = 0; i < 5; ++i) now += link.connection_failed(now).delay;
  EXPECT_EQ(link.failed_attempts(), 5u);
  EXPECT_EQ(link.rejoins(), 0u);

  // A new connection: the full handshake again, with a new nonce; the Welcome is the success.
  MasterHandshake restarted(secret(), "dome");
  const Welcome welcome = handshake(link, restarted);
  EXPECT_TRUE(link.reconnecting()) << "only a Welcome counts as success, not a connection";
  EXPECT_EQ(link.on_message(welcome).meaning, Meaning::welcomed);
  EXPECT_FALSE(link.reconnecting());
  EXPECT_EQ(link.failed_attempts(), 0u);
  EXPECT_EQ(link.rejoins(), 1u);

  // Lost again much later: the whole reconnect time again, and again at once.
  now += std::chrono::seconds(1000);
  const MasterLinkProtocol::Retry r = link.connection_failed(now);
  EXPECT_FALSE(r.give_up);
  EXPECT_EQ(r.delay.count(), 0);
  EXPECT_EQ(link.deadline(), now + milliseconds(30000));
  EXPECT_EQ(link.connection_failed(now).delay.count(),
            static_cast<std::int64_t>(100 * MasterLinkProtocol::jitter_factor(link.rules(), "left", 1)))
      << "the backoff starts from the first wait again";
}

TEST(MasterLinkProtocol, EachConnectionRunsTheWholeHandshakeWithAFreshNonce) {
  MasterLinkProtocol link = node_link();
  const Hello one = link.start();
  const Hello two = link.start();
  EXPECT_NE(one.node_nonce, two.node_nonce);
  MasterHandshake master(secret(), "dome");
  EXPECT_EQ(link.on_message(handshake(link, master)).meaning, Meaning::welcomed)
      << "a Welcome answers the handshake of the connection in use";
}

TEST(MasterLinkProtocol, AReconnectTimeOfZeroGivesUpAtTheFirstLoss) {
  MasterLinkProtocol link = node_link(rules(0));
  MasterHandshake master(secret(), "dome");
  (void)link.on_message(handshake(link, master));
  EXPECT_TRUE(link.connection_failed(t0 + std::chrono::seconds(5)).give_up);
}

TEST(MasterLinkProtocol, BeforeTheFirstWelcomeFailuresCountAgainstTheConnectTimeout) {
  MasterLinkProtocol link = node_link();
  EXPECT_FALSE(link.reconnecting());
  auto now = t0;
  for (;;) {
    const MasterLinkProtocol::Retry r = link.connection_failed(now);
    if (r.give_up) break;
    now += r.delay;
  }
  EXPECT_EQ(now, t0 + milliseconds(20000)) << "the connect timeout, not the reconnect time";
}

// ---- the listed masters: the active master, then the standby ----------------

/// A node of a cluster with a standby (two listed masters, the node's attempt limit), begun at t0.
MasterLinkProtocol node_with_standby(ReconnectRules r = rules()) {
  r.attempt_timeout_ms = attempt_timeout_ms_for(2);
  MasterLinkProtocol link(secret(), "dome", "left", 250, r, 2);
  link.begin(t0);
  return link;
}

TEST(MasterLinkProtocol, TheListedMastersAreTheActiveThenTheStandby) {
  ClusterConfig config;
  config.master_host = "10.0.0.1";
  config.master_port = 47100;
  EXPECT_EQ(listed_masters(config, std::nullopt), (std::vector<MasterAddress>{{"10.0.0.1", 47100}}));
  EXPECT_EQ(listed_masters(config, 5000), (std::vector<MasterAddress>{{"10.0.0.1", 5000}})) << "--port";
  config.standby = MasterAddress{"10.0.0.2", 47101};
  EXPECT_EQ(listed_masters(config, 5000), (std::vector<MasterAddress>{{"10.0.0.1", 5000}, {"10.0.0.2", 47101}}))
      << "--port overrides the active master's port only";
  EXPECT_EQ(attempt_timeout_ms_for(1), 0u) << "one master: as without standbys";
  EXPECT_EQ(attempt_timeout_ms_for(2), 3000u);
}

TEST(MasterLinkProtocol, EachListedMasterIsTriedInTurnAndTheBackoffCountsRounds) {
  MasterLinkProtocol link = node_with_standby();
  EXPECT_EQ(link.master_count(), 2u);
  EXPECT_EQ(link.master_index(), 0u) << "the active master first";
  auto now = t0;
  for (std::uint32_t round = 1; round <= 6; ++round) {
    const MasterLinkProtocol::Retry to_standby = link.connection_failed(now);
    EXPECT_FALSE(to_standby.give_up);
    EXPECT_EQ(to_standby.delay.count(), 0) << "the standby at once after the active master, round " << round;
    EXPECT_EQ(link.master_index(), 1u);
    const MasterLinkProtocol::Retry to_active = link.connection_failed(now);
    EXPECT_EQ(link.master_index(), 0u) << "then the active master again, after the wait";
    EXPECT_EQ(to_active.delay.count(),
              static_cast<std::int64_t>(static_cast<double>(MasterLinkProtocol::backoff(link.rules(), round).count()) *
                                        MasterLinkProtocol::jitter_factor(link.rules(), "left", round)))
        << "round " << round;
    now += to_active.delay;
  }
  EXPECT_EQ(link.failed_attempts(), 12u);
  EXPECT_EQ(link.attempt_limit(), std::nullopt) << "the first connection may wait for a master preparing its tables";
}

TEST(MasterLinkProtocol, AfterALossTheActiveMasterIsTriedFirstThenTheStandbyEachWithinTheAttemptLimit) {
  MasterLinkProtocol link = node_with_standby();
  MasterHandshake active(secret(), "dome");
  (void)link.on_message(handshake(link, active));
  const auto lost = t0 + std::chrono::seconds(60);
  const MasterLinkProtocol::Retry first = link.connection_failed(lost);  // the active master is gone
  EXPECT_EQ(first.delay.count(), 0);
  EXPECT_EQ(link.master_index(), 0u) << "it may have restarted: the active master first";
  EXPECT_EQ(link.attempt_limit(), std::optional<milliseconds>(3000)) << "a stopped master must not hold the node";
  const MasterLinkProtocol::Retry refused = link.connection_failed(lost + milliseconds(2));
  EXPECT_EQ(refused.delay.count(), 0);
  EXPECT_EQ(link.master_index(), 1u) << "then the standby, at once";

  // The standby (which took over) welcomes it: it is the master in use now.
  MasterHandshake standby(secret(), "dome");
  EXPECT_EQ(link.on_message(handshake(link, standby)).meaning, Meaning::welcomed);
  EXPECT_EQ(link.master_index(), 1u);
  EXPECT_EQ(link.rejoins(), 1u);
  EXPECT_EQ(link.attempt_limit(), std::nullopt);

  // Lost again: the list from the top (the active master, then the standby).
  (void)link.connection_failed(lost + std::chrono::seconds(100));
  EXPECT_EQ(link.master_index(), 0u);
  EXPECT_EQ(link.deadline(), lost + std::chrono::seconds(100) + milliseconds(30000));
}

TEST(MasterLinkProtocol, WithTwoMastersTheReconnectTimeStillEndsTheLink) {
  MasterLinkProtocol link = node_with_standby();
  MasterHandshake active(secret(), "dome");
  (void)link.on_message(handshake(link, active));
  auto now = t0 + std::chrono::seconds(1);
  (void)link.connection_failed(now);  // lost
  int attempts = 0;
  for (;;) {
    const MasterLinkProtocol::Retry r = link.connection_failed(now);
    if (r.give_up) break;
    now += r.delay;
    ASSERT_LT(++attempts, 200);
  }
  EXPECT_EQ(now, t0 + std::chrono::seconds(1) + milliseconds(30000));
}

TEST(MasterLinkProtocol, AStandbyFollowsItsMasterInTheStandbyRole) {
  ReconnectRules r = rules();
  r.attempt_timeout_ms = 1000;
  MasterLinkProtocol link(secret(), "dome", "standby@h:2", 250, r, 1, PeerRole::standby);
  link.begin(t0);
  const Hello hello = link.start();
  EXPECT_EQ(hello.role, PeerRole::standby);
  MasterHandshake master(secret(), "dome");
  const MasterLinkProtocol::Step answer = link.on_message(master.on_hello(hello));
  ASSERT_TRUE(answer.reply.has_value());
  EXPECT_NO_THROW(master.on_authenticate(std::get<Authenticate>(*answer.reply)));
  EXPECT_EQ(link.on_message(master.welcome(1, 5, 250, 1000)).meaning, Meaning::welcomed);
  (void)link.connection_failed(t0 + std::chrono::seconds(1));
  EXPECT_EQ(link.attempt_limit(), std::optional<milliseconds>(1000)) << "its check that the master is gone";
}

}  // namespace
}  // namespace zenith::cluster
