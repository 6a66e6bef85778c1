// How a connection ends (cluster/link/connection.h), on real loopback
// sockets: close_after_flush sends what is queued, ends its side, and closes
// only once the peer has closed too — never with the peer's bytes unread,
// which would make the kernel reset the connection and drop what the peer
// had not acknowledged (on a lossy link, the master's Goodbye) — and gives up
// after its grace when the peer never closes.
#include "cluster/link/connection.h"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>

#include "cluster/protocol/frame_decoder.h"
#include "cluster/protocol/messages.h"

namespace zenith::cluster {
namespace {

namespace asio = boost::asio;
using tcp = asio::ip::tcp;
using namespace std::chrono_literals;

class ConnectionEndTest : public ::testing::Test {
 protected:
  ConnectionEndTest() : acceptor_(io_, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)), peer_(io_) {
    peer_.connect(acceptor_.local_endpoint());
    connection_ = std::make_shared<Connection>(acceptor_.accept(), "peer");
    connection_->start([this](Message&&) { ++handled_; }, [this](const std::string& reason) { closed_ = reason; });
  }
  /// The peer sends a Heartbeat the connection has not read yet.
  void peer_sends_unread_bytes() {
    const std::vector<std::uint8_t> frame = encode(Heartbeat{});
    asio::write(peer_, asio::buffer(frame));
  }
  /// What the peer reads until its stream ends, and how it ended.
  std::vector<Message> peer_reads_to_the_end(boost::system::error_code& end) {
    FrameDecoder decoder;
    std::vector<std::uint8_t> chunk(4096);
    std::vector<Message> messages;
    for (int reads = 0; reads < 1000; ++reads) {
      const std::size_t n = peer_.read_some(asio::buffer(chunk), end);
      if (end) break;
      decoder.feed(std::span<const std::uint8_t>(chunk.data(), n));
      while (std::optional<Message> m = decoder.next()) messages.push_back(std::move(*m));
    }
    return messages;
  }

  asio::io_context io_;
  tcp::acceptor acceptor_;
  tcp::socket peer_;
  std::shared_ptr<Connection> connection_;
  int handled_ = 0;
  std::optional<std::string> closed_;
};

TEST_F(ConnectionEndTest, AGoodbyeEndsTheStreamCleanlyAndTheConnectionClosesAfterThePeer) {
  peer_sends_unread_bytes();
  connection_->send(Goodbye{"master stopping"});
  connection_->close_after_flush("master stopping", 5s);
  io_.run_for(300ms);
  EXPECT_FALSE(closed_) << "closed before the peer did: " << *closed_;

  boost::system::error_code end;
  const std::vector<Message> received = peer_reads_to_the_end(end);
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(std::get<Goodbye>(received[0]).reason, "master stopping");
  EXPECT_EQ(end, asio::error::eof) << "the stream ended by " << end.message() << ", not its end";

  peer_.close();
  io_.restart();
  io_.run_for(1s);
  ASSERT_TRUE(closed_) << "the connection did not close after the peer";
  EXPECT_EQ(*closed_, "master stopping");
  EXPECT_EQ(handled_, 0) << "a message received while closing was handled";
}

TEST_F(ConnectionEndTest, APeerThatNeverClosesIsLeftAfterTheGrace) {
  peer_sends_unread_bytes();
  connection_->send(Goodbye{"master stopping"});
  const auto start = std::chrono::steady_clock::now();
  connection_->close_after_flush("master stopping", 400ms);
  io_.run_for(200ms);
  EXPECT_FALSE(closed_);
  io_.restart();
  io_.run_for(2s);  // returns when nothing is left to do: the grace timer fired and the connection closed
  ASSERT_TRUE(closed_);
  EXPECT_EQ(*closed_, "master stopping");
  EXPECT_GE(std::chrono::steady_clock::now() - start, 400ms);
}

}  // namespace
}  // namespace zenith::cluster
