#pragma once
// The node's side of its link to the master as pure logic (docs/cluster.md,
// "Join, rejoin and failures"; docs/protocol.md, "Handshake"): the handshake
// (Hello, Authenticate, the master's proof in Welcome), what each message from
// the master means for the link, when the master counts as silent, and the
// reconnection rules — which listed master to try (the active master, then
// the standby: docs/cluster.md, "Standby master"), when to try again after a
// failed attempt or a lost connection, and when to give up. No sockets and no clock: MasterLink
// (cluster/link/master_link.h) feeds it the messages and the clock readings
// and does what it answers.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cluster/link/cluster_config.h"
#include "cluster/protocol/handshake.h"
#include "cluster/protocol/messages.h"

namespace zenith::cluster {

/// How a node connects and reconnects to its master (docs/cluster.md, "Join,
/// rejoin and failures").
struct ReconnectRules {
  /// The first connection must be welcomed within this (the master may be
  /// preparing tables: `zenith cluster` gives its nodes 15 minutes).
  std::uint32_t connect_timeout_ms = 15000;
  /// After a welcomed connection is lost, a new one must be welcomed within
  /// this; 0: no reconnection, the node exits at once.
  std::uint32_t reconnect_ms = kDefaultReconnectMs;
  /// The wait before the second attempt; it doubles with every failed
  /// attempt up to max_retry_ms. The first attempt after a loss is immediate.
  std::uint32_t first_retry_ms = 100;
  std::uint32_t max_retry_ms = 2000;
  /// Every wait is scaled by a factor in [1 − jitter, 1 + jitter] drawn from
  /// the node's name and the attempt, so that the nodes of a restarted master
  /// do not all knock at the same instant (and a test can predict it).
  double jitter = 0.2;
  /// While reconnecting after a loss, an attempt that brings no Welcome within
  /// this is given up and the next listed master tried (a master that is
  /// stopped, not dead, still accepts connections in its kernel backlog);
  /// 0: no limit but the deadline. Not applied to the first connection, whose
  /// master may be preparing its tables for minutes before its Welcome.
  std::uint32_t attempt_timeout_ms = 0;
};

/// Where a node looks for its master (docs/cluster.md, "Standby master"): the
/// active master (its port replaced by `port` when given), then the standby
/// when the configuration has one.
std::vector<MasterAddress> listed_masters(const ClusterConfig& config, std::optional<std::uint16_t> port);

/// The attempt limit a node uses with `masters` listed masters: 3 s when there
/// is a standby to turn to, none otherwise (ReconnectRules::attempt_timeout_ms).
std::uint32_t attempt_timeout_ms_for(std::size_t masters);

/// Invariants: before Welcome only the handshake's messages are accepted
/// (anything else throws) and the node sends no Heartbeat; the master may stay
/// silent until the deadline of the attempt (it may still be preparing
/// tables). From Welcome on, the master's heartbeat interval applies: a
/// Heartbeat per tick, and the master counts as silent after
/// silence_limit_ms() of it. Reject, a Goodbye or a failed proof end the link
/// for good; any other end of a connection is a failed attempt (before
/// Welcome) or a loss (after it), and the link tries again until its deadline:
/// the connect timeout from begin(), the reconnect time from a loss. Only a
/// Welcome counts as success: it resets the attempts and the deadline.
///
/// With several listed masters (the active master, then the standby), every
/// attempt goes to master_index(): after a failed attempt the next listed
/// master is tried at once, and only after the last one does the link wait
/// (the backoff counts these rounds through the list); a loss starts again at
/// the first. With one master this is the plain backoff above.
class MasterLinkProtocol {
 public:
  using Clock = std::chrono::steady_clock;

  /// `heartbeat_ms`: the configuration's, until Welcome brings the master's;
  /// `masters`: how many masters are listed (at least 1); `role`: what this
  /// side says it is in its Hello (a node, or a standby following its master).
  MasterLinkProtocol(SharedSecret secret, std::string cluster_name, std::string node_name, std::uint32_t heartbeat_ms,
                     ReconnectRules rules, std::size_t masters = 1, PeerRole role = PeerRole::node);

  /// The link starts (before its first attempt): the connect timeout counts from `now`.
  void begin(Clock::time_point now);

  /// A new connection: the handshake starts afresh (new nonce); returns the Hello to send.
  Hello start();

  /// What a message from the master means for the link.
  enum class Meaning {
    reply,      ///< a step of the handshake: send Step::reply
    welcomed,   ///< Welcome, and the master proved the secret: the node may declare its tables
    work,       ///< after Welcome, a message for the node (frames, tables, …)
    heartbeat,  ///< after Welcome: nothing to do (liveness counts the bytes received)
    rejected,   ///< Reject: the master refused the node (exit kNodeExitRefused)
    goodbye,    ///< Goodbye: before Welcome a refusal (kNodeExitRefused), after it the show's end (kNodeExitDone)
  };
  struct Step {
    Meaning meaning = Meaning::work;
    std::optional<Message> reply;  ///< Meaning::reply
  };
  /// Throws HandshakeError when the master fails to prove the secret, and
  /// std::runtime_error for a message out of place before Welcome.
  Step on_message(const Message& message);

  bool welcomed() const { return welcomed_; }
  /// The session's datagram key (handshake.h); only once welcomed.
  Digest datagram_key() const { return handshake_->datagram_key(); }
  /// Between ticks and Heartbeats: the configuration's before Welcome, the master's after.
  std::uint32_t heartbeat_ms() const { return heartbeat_ms_; }
  /// After Welcome: silence after which the master counts as silent,
  /// silence_limit_ms(heartbeat_ms()) (cluster_config.h).
  double silence_limit_ms() const;

  /// What to do at a heartbeat tick, with bytes last received from the master at `last_received`.
  enum class Tick {
    wait,            ///< before Welcome, the deadline not reached
    send_heartbeat,  ///< after Welcome, the master alive
    silent,          ///< after Welcome nothing for silence_limit_ms(), before it the deadline passed:
                     ///< close the connection and call connection_failed()
  };
  Tick tick(Clock::time_point last_received, Clock::time_point now) const;

  /// When to make the next attempt, or that the link gives up.
  struct Retry {
    bool give_up = false;
    std::chrono::milliseconds delay{0};  ///< wait this long, then connect (unless give_up)
  };
  /// The connection in use ended without Reject or Goodbye (closed, silent, an
  /// error), or an attempt failed (refused, unreachable, closed before
  /// Welcome). After Welcome this is a loss: the reconnect time starts and the
  /// first new attempt is immediate (give up at once when it is 0). Otherwise
  /// the next listed master is tried at once; after the last, the wait
  /// doubles per round from first_retry_ms up to max_retry_ms (with jitter),
  /// never past the deadline; at the deadline, give up. A loss goes back to
  /// the first listed master.
  Retry connection_failed(Clock::time_point now);

  /// A welcomed connection was lost and no new one is welcomed yet.
  bool reconnecting() const { return reconnecting_; }
  /// Failed attempts since the last Welcome (or begin()).
  std::uint32_t failed_attempts() const { return failed_attempts_; }
  /// The listed master the next (or current) attempt goes to: 0 the active
  /// master, 1 the standby. After a Welcome, the one that welcomed.
  std::size_t master_index() const { return master_index_; }
  std::size_t master_count() const { return masters_; }
  /// The time an attempt (connect and handshake) may take before it is given
  /// up: rules().attempt_timeout_ms while reconnecting after a loss; none
  /// otherwise, or when it is 0.
  std::optional<std::chrono::milliseconds> attempt_limit() const;
  /// Welcomes after the first: how often the node rejoined.
  std::uint32_t rejoins() const { return rejoins_; }
  /// The time by which a connection must be welcomed (meaningless after Welcome).
  Clock::time_point deadline() const { return deadline_; }
  const ReconnectRules& rules() const { return rules_; }

  /// The nominal wait before attempt `failed + 1` after `failed` failed
  /// attempts (failed ≥ 1), before jitter: first_retry_ms × 2^(failed−1), at
  /// most max_retry_ms.
  static std::chrono::milliseconds backoff(const ReconnectRules& rules, std::uint32_t failed);
  /// The jitter factor of attempt `failed` of node `node_name`, in [1 − jitter, 1 + jitter].
  static double jitter_factor(const ReconnectRules& rules, const std::string& node_name, std::uint32_t failed);

 private:
  SharedSecret secret_;
  std::string cluster_name_, node_name_;
  std::uint32_t heartbeat_ms_;
  ReconnectRules rules_;
  std::size_t masters_;
  PeerRole role_;
  std::optional<NodeHandshake> handshake_;
  /// This process's Hello.instance_id, the same on every connection: a
  /// rejoin after a drop replaces the old connection at the master.
  std::uint64_t instance_id_ = random_instance_id();
  bool welcomed_ = false;
  bool ever_welcomed_ = false;
  bool reconnecting_ = false;
  std::uint32_t failed_attempts_ = 0;
  std::uint32_t failed_rounds_ = 0;  ///< times through the whole list since the last Welcome (or begin())
  std::size_t master_index_ = 0;
  std::uint32_t rejoins_ = 0;
  Clock::time_point deadline_{};
};

}  // namespace zenith::cluster
