#pragma once
// The master's listening socket (docs/cluster.md, "Join, rejoin and
// failures"): every accepted connection becomes a node session in its
// handshake (NodeSessions), whose messages and close go to the master's
// handlers on the io_context's thread. Nodes that start before the master
// listens are queued by the kernel and served once it accepts.
#include <cstdint>
#include <functional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "cluster/link/accept_retry.h"
#include "cluster/master/node_sessions.h"
#include "cluster/protocol/handshake.h"
#include "cluster/protocol/messages.h"
#include "core/log_limiter.h"

namespace zenith::cluster {

/// Invariant: after close() no connection is accepted and no handler is called for a new one.
class NodeListener {
 public:
  using OnMessage = std::function<void(std::uint32_t session, Message&& message)>;
  using OnClosed = std::function<void(std::uint32_t session, const std::string& reason)>;

  /// Sessions go into `sessions`, authenticated with `secret` for cluster `cluster_name`.
  NodeListener(boost::asio::io_context& io, NodeSessions& sessions, SharedSecret secret, std::string cluster_name,
               OnMessage on_message, OnClosed on_closed);

  /// Binds host:port (address reuse on) and listens. Throws
  /// std::runtime_error "master: cannot listen on HOST:PORT: REASON".
  void listen(const std::string& host, std::uint16_t port);
  /// At most `max_connections` connections in the handshake at once (the
  /// oldest is closed for a new one); default kDefaultMaxUnauthenticatedConnections.
  void limit_unauthenticated(std::uint32_t max_connections);
  /// Accepts connections until close().
  void start();
  void close();

 private:
  void accept();
  void on_accept(boost::asio::ip::tcp::socket socket);

  boost::asio::ip::tcp::acceptor acceptor_;
  AcceptRetry accept_retry_;
  core::LogLimiter refusals_;
  std::uint32_t max_unauthenticated_ = kDefaultMaxUnauthenticatedConnections;
  NodeSessions& sessions_;
  SharedSecret secret_;
  std::string cluster_name_;
  OnMessage on_message_;
  OnClosed on_closed_;
  bool closed_ = false;
};

}  // namespace zenith::cluster
