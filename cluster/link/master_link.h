#pragma once
// A render node's link to its master, on the node's networking thread
// (docs/cluster.md, "Architecture"; "Join, rejoin and failures"): resolves
// the address of a listed master (the active master, then the standby) and
// connects, retrying with backoff up to the connect timeout; runs the handshake and the heartbeats; when a welcomed
// connection is lost (closed, or the master silent), tells the node and reconnects — a full handshake again — until the
// reconnect time runs out (MasterLinkProtocol: the rules, without sockets). It hands the node every message of the
// master after each Welcome, and tells it when the link ends and with which exit code. What the messages mean for
// tables, frames and files is the node's (cluster/node/node.cpp). A standby master follows its active master through
// the same link, in the standby role (cluster/standby/standby.h).
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>

#include "cluster/link/connection.h"
#include "cluster/link/link_exit.h"
#include "cluster/link/master_link_protocol.h"

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
    /// Optional: an attempt failed (refused, unreachable, closed or no Welcome
    /// in time; not a loss) and the link is about to retry. The handler may
    /// call stop() to end the link here (a standby takes over).
    std::function<void(const std::string& reason)> attempt_failed = nullptr;
  };

  /// Who connects to which masters, and how.
  struct Setup {
    std::string cluster_name;
    std::string peer_name;  ///< the name in the Hello
    PeerRole role = PeerRole::node;
    std::string who;                     ///< "node 'a'", "standby": the start of every log line
    std::vector<MasterAddress> masters;  ///< tried in order (listed_masters())
    std::uint32_t heartbeat_ms = 250;    ///< the configuration's, until the Welcome brings the master's
    ReconnectRules rules;
  };
  MasterLink(boost::asio::io_context& io, Setup setup, SharedSecret secret, Events events);
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

  /// The welcomed connection's master (address and port) and the session's
  /// datagram key (cluster/protocol/datagram.h); nothing while not welcomed.
  std::optional<boost::asio::ip::tcp::endpoint> master_endpoint() const;
  std::optional<Digest> datagram_key() const;
  /// "host:port" of the master in use (or tried next), for logs.
  std::string master_address() const;

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
  /// Every listed master, "host:port, host:port", for logs.
  std::string listed() const;
  /// Closes the socket of a connect still in progress (an attempt that timed
  /// out, or the link stopping): a master whose machine dropped off the
  /// network never answers, and the pending connect would keep the
  /// io_context running for the kernel's SYN retries (about two minutes).
  void abandon_connect();

  boost::asio::io_context& io_;
  Setup setup_;
  Events events_;
  MasterLinkProtocol protocol_;
  /// heartbeat_timer_ ticks while connected; retry_timer_ waits between
  /// attempts; attempt_timer_ ends an attempt past the protocol's attempt limit.
  boost::asio::steady_timer heartbeat_timer_, retry_timer_, attempt_timer_;
  std::shared_ptr<Connection> connection_;
  std::shared_ptr<boost::asio::ip::tcp::socket> connecting_;  ///< the socket of a connect in progress
  /// Counts connections and attempts: handlers of an earlier one see another number and do nothing.
  std::uint64_t generation_ = 0;
  std::chrono::steady_clock::time_point connect_started_, lost_at_;
  std::string last_failure_;  ///< why the last attempt failed, for the give-up message
  bool stopping_ = false;
};

}  // namespace zenith::cluster
