#pragma once
// A render node's link to its master, on the node's networking thread
// (docs/cluster.md, "Architecture"; "Join, rejoin and failures"): resolves
// the master's address and connects, retrying with backoff up to the connect
// timeout; runs the handshake and the heartbeats; when a welcomed connection
// is lost (closed, or the master silent), tells the node and reconnects —
// a full handshake again — until the reconnect time runs out
// (MasterLinkProtocol: the rules, without sockets). It hands the node every
// message of the master after each Welcome, and tells it when the link ends
// and with which exit code. What the messages mean for tables, frames and
// files is the node's (cluster/node.cpp).
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>

#include "cluster/connection.h"
#include "cluster/node.h"
#include "cluster/node/master_link_protocol.h"

namespace zenith::cluster {

/// Every member function, and every event, runs on the thread running the
/// io_context. Invariants: events come only until the link stops (stop(),
/// or the end it reports through Events::ended); Events::message only
/// between an Events::welcomed and the next Events::lost; at most one
/// connection at a time, and the handlers and timers of an earlier one do
/// nothing.
class MasterLink {
 public:
  struct Events {
    /// The master proved the secret (the node declares its tables: send()).
    /// Again after every reconnection.
    std::function<void(const Welcome& welcome)> welcomed;
    /// A welcomed connection was lost without Goodbye; the link reconnects
    /// (the node forgets the frame in flight and keeps showing the last one).
    std::function<void(const std::string& reason)> lost;
    /// A message of the master after Welcome, but Heartbeat and Goodbye. A
    /// throw closes the link with a Goodbye naming the error (kNodeExitFailed).
    std::function<void(const Message& message)> message;
    /// The link ended (the master's Goodbye, refused, the reconnect time ran out, an error):
    /// the node finishes with `exit_code` (NodeExit) and calls stop().
    std::function<void(int exit_code)> ended;
  };

  MasterLink(boost::asio::io_context& io, const NodeOptions& options, SharedSecret secret, Events events);
  MasterLink(const MasterLink&) = delete;
  MasterLink& operator=(const MasterLink&) = delete;

  /// Starts connecting; the connect timeout counts from here.
  void start();
  /// Queues `message` for the master: false (and nothing sent) when not
  /// connected and welcomed, or stopping.
  bool send(const Message& message);
  /// Leaving: sends Goodbye{reason} and closes once it is flushed (when connected).
  void say_goodbye(const std::string& reason);
  /// Stops: no more events, timers cancelled, the connection closed once its queue is flushed.
  void stop();

  bool stopping() const { return stopping_; }
  /// "host:port", for logs.
  const std::string& master_address() const { return master_address_; }

 private:
  void connect();
  void on_connected(boost::asio::ip::tcp::socket socket);
  void on_closed(const std::string& reason);
  void on_message(Message&& message);
  void heartbeat_tick(std::uint64_t generation);
  /// The connection (or an attempt) failed without Reject or Goodbye: closes
  /// it, tells the node of a loss, and retries or gives up (MasterLinkProtocol).
  void connection_failed(const std::string& reason);
  /// The link ends here: stopping, closed now (Reject, Goodbye), then Events::ended.
  void end(const std::string& close_reason, int exit_code);

  boost::asio::io_context& io_;
  const NodeOptions& options_;
  Events events_;
  MasterLinkProtocol protocol_;
  std::uint16_t port_;
  std::string master_address_;
  boost::asio::steady_timer heartbeat_timer_, retry_timer_;
  std::shared_ptr<Connection> connection_;
  /// Counts connections and attempts: handlers of an earlier one see another number and do nothing.
  std::uint64_t generation_ = 0;
  std::chrono::steady_clock::time_point connect_started_, lost_at_;
  std::string last_failure_;  ///< why the last attempt failed, for the give-up message
  bool stopping_ = false;
};

}  // namespace zenith::cluster
