#pragma once
// The master's datagram port (docs/cluster.md, "The frame schedule";
// docs/protocol.md, "Datagrams"): a UDP socket on the master's port number.
// It answers each node's ClockPing at once with a ClockPong (the node's
// clock estimate) and learns from it where the node's scheduled frames go;
// send_frame() sends one (FrameSchedule + FrameState) there. A datagram whose
// node id names no authenticated session, or whose tag fails, is dropped with
// a rate-limited line.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>

#include "cluster/master/node_sessions.h"
#include "cluster/protocol/messages.h"
#include "core/log_limiter.h"

namespace zenith::cluster {

class NodeDatagrams {
 public:
  using Clock = std::chrono::steady_clock;
  /// A node not heard on UDP for this long gets its frames over TCP (a firewall
  /// that drops UDP, a node of an older build); its pings come every 100 ms.
  static constexpr std::chrono::milliseconds kSilence{3000};
  /// A node heard on UDP and then silent for this long (five pings) is
  /// unreachable: logged, and so in the status, until its next datagram.
  static constexpr std::chrono::milliseconds kQuiet{500};

  NodeDatagrams(boost::asio::io_context& io, NodeSessions& sessions);
  /// Binds host:port (UDP) and starts answering. A failure is logged, not
  /// thrown: every node then gets its frames over TCP.
  void open(const std::string& host, std::uint16_t port);
  void close();
  bool is_open() const { return socket_.has_value(); }

  /// Whether `session`'s datagrams came recently enough to send it frames that way.
  bool reaches(const NodeSession& session, Clock::time_point now) const;
  /// The heartbeat tick: nodes that fell silent on UDP are logged (once);
  /// `black`: the config's timing.link_lost (what their projectors show).
  void check_links(Clock::time_point now, bool black);
  /// Sends `datagram` (sealed for `session`) to the node's datagram address.
  void send(const NodeSession& session, std::shared_ptr<const std::vector<std::uint8_t>> datagram);

 private:
  void receive();
  void on_datagram(std::size_t bytes, const boost::asio::ip::udp::endpoint& from);

  NodeSessions& sessions_;
  boost::asio::io_context& io_;
  std::optional<boost::asio::ip::udp::socket> socket_;
  boost::asio::ip::udp::endpoint sender_;
  std::vector<std::uint8_t> buffer_;
  core::LogLimiters refused_;
};

}  // namespace zenith::cluster
