#pragma once
// One node's connection to the master and what the master knows about it
// (docs/cluster.md, "Join, rejoin and failures"): where it is in the
// handshake, its name, and which table sets it holds.
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include <boost/asio/ip/udp.hpp>

#include "cluster/link/connection.h"
#include "cluster/protocol/handshake.h"

namespace zenith::cluster {

/// A session lives from the accepted connection to its close; a node that
/// reconnects gets a new session with a new id.
///
/// States: `handshake` (Hello … Authenticate) → `tables` (Welcome sent: the
/// inventory, then the sets it lacks) → `ready` (holds every current set:
/// takes part in frames from the next boundary). A session never goes back.
struct NodeSession {
  enum class State { handshake, tables, ready };

  std::uint32_t id = 0;  ///< never reused within a master's run
  std::shared_ptr<Connection> connection;
  std::optional<MasterHandshake> handshake;
  State state = State::handshake;
  std::string name;               ///< from Hello (empty before)
  std::uint64_t instance_id = 0;  ///< from Hello: the peer process (docs/protocol.md, "Hello")
  /// From Hello: a render node, or a standby master (docs/cluster.md, "Standby
  /// master"), which is sent every table set and frame but never becomes ready.
  PeerRole role = PeerRole::node;
  /// The node's cache inventory: the TableReady messages it sends right after
  /// Welcome, up to its first other message (a Heartbeat), name the sets it
  /// already holds; those are announced to it but never sent again.
  bool inventory_done = false;
  std::set<Digest> cached;
  std::set<Digest> tables_ready;  ///< TableReady after the inventory: held, verified and loaded
  std::uint64_t chunks_sent = 0;
  /// The table bytes sent to it (AtmosphereDefinitions, announcements and
  /// chunks) since its inventory ended, and when that was: the time it takes
  /// to become ready is its link's and its loading's (logged, in the status).
  std::uint64_t table_bytes_sent = 0;
  std::chrono::steady_clock::time_point inventory_done_at{};
  std::chrono::steady_clock::time_point connected_at = std::chrono::steady_clock::now();
  /// Datagrams (cluster/protocol/datagram.h): the session's key, once
  /// authenticated; where its ClockPings come from (where its scheduled
  /// frames go), and when the last one came: a node silent on UDP for
  /// kDatagramSilenceMs gets its frames over TCP.
  std::optional<Digest> datagram_key;
  std::optional<boost::asio::ip::udp::endpoint> datagram_peer;
  std::chrono::steady_clock::time_point last_datagram{};
  /// No datagram for NodeDatagrams::kQuiet: its link is cut (logged once, and again when it is back).
  bool link_quiet = false;
  /// During a link check (cluster/check/link_check.h): the stamps of the
  /// distinct ClockPings heard from it.
  std::optional<std::set<std::uint64_t>> link_check_pings;

  /// "node 'a' (127.0.0.1:5000)", "the standby (127.0.0.1:5000)", or "connection from 127.0.0.1:5000" before Hello: for
  /// logs.
  std::string who() const;
  /// Refuses the handshake: Reject with `reason` and `text`, then close
  /// (log line, unless `log` is false: NodeSessions::refuse rate-limits them).
  void refuse(RejectReason reason, const std::string& text, bool log = true);
  /// Closes for a message a node must not send: Goodbye naming it, then close (log line).
  void close_for_protocol_violation(const std::string& what);
};

}  // namespace zenith::cluster
