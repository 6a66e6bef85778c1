#pragma once
// OSC over UDP for show-control desks (docs/operator.md, "OSC"), on the
// master's own io_context: every datagram is decoded (osc_packet.h), each of
// its messages turned into an operator command (osc_command.h) and handed to
// the master on its networking thread, between frames. Each message is
// applied or refused with a log line (the master's, or the receiver's for
// packets that do not decode and senders that are not allowed).
//
// Security: OSC has no authentication, so the receiver listens on the
// loopback interface unless told otherwise, and on any other interface only
// accepts datagrams from the sender addresses it is given (a desk's fixed
// address on the show-control network).
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>

#include "cluster/operator/operator_command.h"
#include "cluster/operator/osc_packet.h"
#include "core/log_limiter.h"

namespace zenith::cluster {

/// Invariant: after close() no datagram is handled.
class OscReceiver {
 public:
  struct Options {
    std::string host = "127.0.0.1";            ///< address to listen on
    std::uint16_t port = 0;                    ///< 0: any free port (see port())
    std::vector<std::string> allowed_senders;  ///< numeric IPs; required when `host` is not a loopback address
  };
  /// Applies a command from `source` ("osc 10.0.0.5") and returns the reply;
  /// throws when refused. It logs either way.
  using CommandHandler = std::function<std::string(const OperatorCommand& command, const std::string& source)>;

  OscReceiver(boost::asio::io_context& io, Options options, CommandHandler on_command);
  OscReceiver(const OscReceiver&) = delete;
  OscReceiver& operator=(const OscReceiver&) = delete;

  /// Binds and starts receiving. Throws std::runtime_error for an address that
  /// is not a numeric IP, a port that cannot be bound, or a non-loopback
  /// address without allowed senders.
  void start();
  std::uint16_t port() const { return port_; }
  void close();

  /// Handles one datagram from `sender` (no socket: the tests call it).
  /// Returns how many of its messages were applied.
  std::size_t handle(std::span<const std::uint8_t> datagram, const boost::asio::ip::address& sender);

 private:
  void receive();

  boost::asio::io_context& io_;
  Options options_;
  CommandHandler on_command_;
  std::vector<boost::asio::ip::address> allowed_;
  bool loopback_ = true;
  std::uint16_t port_ = 0;
  std::optional<boost::asio::ip::udp::socket> socket_;
  boost::asio::ip::udp::endpoint sender_;
  std::vector<std::uint8_t> buffer_ = std::vector<std::uint8_t>(kMaxOscPacketBytes + 1);
  bool closed_ = false;
  /// Refusals logged at most once a second each, with the count held back
  /// (a flood of bad packets is a line a second, not a line a packet).
  core::LogLimiter strangers_, malformed_, unknown_;
};

}  // namespace zenith::cluster
