// Who holds a node name (cluster/master/node_sessions.h; docs/protocol.md,
// "Names"): the master's handshake on real loopback
// sockets, the node's side played by NodeHandshake. A second process with a
// connected name is refused, the same process rejoining after a drop replaces
// its old connection, and a holder silent past the limit is taken for dead.
#include "cluster/master/node_sessions.h"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "cluster/link/connection.h"
#include "cluster/protocol/frame_decoder.h"
#include "cluster/protocol/handshake.h"

namespace zenith::cluster {
namespace {

namespace asio = boost::asio;
using tcp = asio::ip::tcp;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

class NodeSessionsTest : public ::testing::Test {
 protected:
  NodeSessionsTest() {
    config_.name = "dome";
    config_.source = "dome.json";
    config_.heartbeat_ms = 200;
    config_.nodes = {{"a", "127.0.0.1", {"left"}}};
  }

  /// A node process of name "a": its socket and its side of the handshake.
  struct Peer {
    std::unique_ptr<tcp::socket> socket;
    NodeHandshake handshake;
    NodeSession* session = nullptr;
  };
  Peer connect(std::uint64_t instance_id) {
    auto client = std::make_unique<tcp::socket>(io_);
    client->connect(acceptor_.local_endpoint());
    auto connection = std::make_shared<Connection>(acceptor_.accept(), "127.0.0.1:" + std::to_string(++peers_));
    NodeSession& session = sessions_.add(connection, MasterHandshake(secret_, "dome"));
    connection->start([](Message&&) {}, [](const std::string&) {});
    return Peer{std::move(client), NodeHandshake(secret_, "dome", "a", PeerRole::node, instance_id), &session};
  }
  /// Hello, Challenge, Authenticate at `now`; throws the master's HandshakeError.
  void authenticate(Peer& peer, Clock::time_point now) {
    sessions_.on_handshake_message(*peer.session, peer.handshake.start(), config_, 7, now);
    const Message challenge = next_message(*peer.socket);
    ASSERT_TRUE(std::holds_alternative<Challenge>(challenge));
    sessions_.on_handshake_message(*peer.session, peer.handshake.on_challenge(std::get<Challenge>(challenge)), config_,
                                   7, now);
  }
  /// A node process `instance_id` connected and authenticated at `now`.
  Peer joined(std::uint64_t instance_id, Clock::time_point now) {
    Peer peer = connect(instance_id);
    authenticate(peer, now);
    return peer;
  }
  /// The next message the master sent on `socket` (its writes run on io_).
  Message next_message(tcp::socket& socket) {
    FrameDecoder decoder;
    const auto deadline = Clock::now() + 5s;
    while (Clock::now() < deadline) {
      io_.poll();
      io_.restart();
      if (socket.available() > 0) {
        std::vector<std::uint8_t> bytes(socket.available());
        bytes.resize(socket.read_some(asio::buffer(bytes)));
        decoder.feed(bytes);
        if (std::optional<Message> m = decoder.next()) return *m;
      }
    }
    throw std::runtime_error("no message from the master within 5 s");
  }

  asio::io_context io_;
  tcp::acceptor acceptor_{io_, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)};
  SharedSecret secret_{std::vector<std::uint8_t>(20, 's'), "test"};
  ClusterConfig config_;
  NodeSessions sessions_;
  int peers_ = 0;
};

TEST_F(NodeSessionsTest, ASecondProcessWithAConnectedNameIsRefusedAndTheHolderKeepsIt) {
  const Clock::time_point now = Clock::now();
  Peer holder = joined(0x1111, now);
  ASSERT_EQ(holder.session->state, NodeSession::State::tables);

  Peer stray = connect(0x2222);
  try {
    authenticate(stray, now + 100ms);
    FAIL() << "a second process took the name";
  } catch (const HandshakeError& e) {
    EXPECT_EQ(e.reason(), RejectReason::duplicate_node);
    EXPECT_NE(std::string(e.what()).find("node 'a' is already connected from 127.0.0.1:1 (another process: instance "
                                         "0000000000001111, this one 0000000000002222): refused"),
              std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(holder.session->connection->is_open()) << "the connected node is not disturbed";
}

TEST_F(NodeSessionsTest, TheSameProcessRejoiningAfterADropReplacesItsOldConnection) {
  const Clock::time_point now = Clock::now();
  Peer first = joined(0x1111, now);
  // Its connection dropped on the node's side; the master has not noticed yet.
  Peer again = joined(0x1111, now + 100ms);
  EXPECT_EQ(again.session->state, NodeSession::State::tables);
  EXPECT_FALSE(first.session->connection->is_open()) << "the old connection is closed for the new one";
}

TEST_F(NodeSessionsTest, AnotherProcessReplacesAHolderSilentPastTheLimit) {
  EXPECT_DOUBLE_EQ(duplicate_alive_ms(200), 2000.0) << "two heartbeats, at least 2 s";
  EXPECT_DOUBLE_EQ(duplicate_alive_ms(5000), 10000.0);
  const Clock::time_point now = Clock::now();
  Peer dead = joined(0x1111, now);
  // Its machine died without closing the socket: nothing received for longer than 2 s.
  Peer successor = joined(0x3333, now + 2500ms);
  EXPECT_EQ(successor.session->state, NodeSession::State::tables);
  EXPECT_FALSE(dead.session->connection->is_open());
}

}  // namespace
}  // namespace zenith::cluster
