#pragma once
// Every node connection of the master, by session id, and the handshake that
// turns a new connection into an authenticated node (docs/protocol.md,
// "Handshake"; docs/cluster.md, "Join, rejoin and failures").
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cluster/link/cluster_config.h"
#include "cluster/master/heartbeat_monitor.h"
#include "cluster/master/node_session.h"
#include "cluster/protocol/messages.h"
#include "core/log_limiter.h"

namespace zenith::cluster {

/// How recently a connection must have received bytes for a second process
/// presenting its name to be refused rather than replace it: two heartbeats,
/// at least 2 s (a live node sends one every heartbeat).
double duplicate_alive_ms(std::uint32_t heartbeat_ms);

/// Owns the sessions; ids count up from 1 and are never reused. Used on the
/// master's networking thread only. Invariant: at most one authenticated
/// session per node name once a handshake completes (a node that reconnects
/// replaces its old connection, which is closed).
class NodeSessions {
 public:
  using Id = std::uint32_t;

  /// A new connection, in the handshake (`handshake` not yet started).
  NodeSession& add(std::shared_ptr<Connection> connection, MasterHandshake handshake);
  /// nullptr when the session is gone.
  NodeSession* find(Id id);
  /// Removes a session and hands it over: its connection is calling back, so
  /// the caller releases it once that handler has returned.
  std::shared_ptr<NodeSession> take(Id id);

  /// Every session's id, in order: a snapshot to iterate while handlers may close sessions.
  std::vector<Id> ids() const;
  /// The sessions still in the handshake whose connection is open, oldest first.
  std::vector<Id> handshake_ids() const;
  /// The ready sessions whose connection is open, in id order.
  std::vector<Id> ready_ids() const;
  std::size_t ready_count() const;
  /// Queues `frame` for every standby master that has been sent the table
  /// sets (its inventory ended): each FrameState and Present (docs/cluster.md, "Standby master").
  void send_to_standbys(const std::shared_ptr<const std::vector<std::uint8_t>>& frame);
  bool empty() const { return sessions_.empty(); }

  /// The heartbeat tick at `now` (HeartbeatMonitor's rule): a Heartbeat to every
  /// open connection that is due one; a connection silent for too long, or
  /// still in its handshake past the limit, closed with a log line naming it.
  void check_heartbeats(const HeartbeatMonitor& monitor, std::chrono::steady_clock::time_point now);
  /// The master is stopping: Goodbye{reason} to every node and standby (Reject
  /// to a connection still in its handshake), each connection closed once
  /// flushed. Their close handlers may remove sessions meanwhile.
  void say_goodbye(const std::string& reason);

  /// Calls `f(NodeSession&)` for every session, in id order; `f` must not add or remove sessions.
  template <typename F>
  void for_each(F&& f) {
    for (auto& [id, session] : sessions_) f(*session);
  }
  template <typename F>
  void for_each(F&& f) const {
    for (const auto& [id, session] : sessions_) f(static_cast<const NodeSession&>(*session));
  }

  /// Refuses `session`'s handshake (NodeSession::refuse) with its log line
  /// escaped and rate-limited: a flood of stray peers costs a line a second,
  /// with the count of those held back.
  void refuse(NodeSession& session, RejectReason reason, const std::string& text);

  /// One handshake message from `session` (state `handshake`): Hello →
  /// Challenge (a node must be in `config`; a standby must be the config's
  /// standby, by standby_name()), Authenticate → Welcome (at
  /// `current_frame`) and state `tables`, closing an older connection of the
  /// same process (Hello.instance_id), or of another process silent for
  /// duplicate_alive_ms() at `now`; Goodbye closes. Throws HandshakeError for
  /// a wrong cluster, version, secret or node, a name another live process
  /// holds (duplicate_node), or any other message.
  void on_handshake_message(NodeSession& session, const Message& message, const ClusterConfig& config,
                            std::uint64_t current_frame,
                            std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());

 private:
  std::map<Id, std::shared_ptr<NodeSession>> sessions_;
  core::LogLimiters refusals_;
  Id next_id_ = 1;
};

}  // namespace zenith::cluster
