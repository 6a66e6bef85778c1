#pragma once
// The node's side of its link to the master as pure logic (docs/cluster.md,
// "Join, rejoin and failures"; docs/protocol.md, "Handshake"): the handshake
// (Hello, Authenticate, the master's proof in Welcome), what each message from
// the master means for the link, and when the master counts as gone. No
// sockets and no clock: MasterLink (cluster/node/master_link.h) feeds it the
// messages and the clock readings and does what it answers.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "cluster/handshake.h"
#include "cluster/messages.h"

namespace zenith::cluster {

/// Invariants: before Welcome only the handshake's messages are accepted
/// (anything else throws), the node sends no Heartbeat and the master may stay
/// silent up to the connect timeout (it may still be preparing tables); from
/// Welcome on, the master's heartbeat interval applies: a Heartbeat per tick,
/// and the master counts as gone after silence_limit_ms() of it. Reject, or a
/// Goodbye, ends the link.
class MasterLinkProtocol {
 public:
  using Clock = std::chrono::steady_clock;

  /// `heartbeat_ms`: the configuration's, until Welcome brings the master's.
  MasterLinkProtocol(SharedSecret secret, std::string cluster_name, std::string node_name, std::uint32_t heartbeat_ms,
                     std::uint32_t connect_timeout_ms);

  /// A new connection: the handshake starts; returns the Hello to send.
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
  /// Between ticks and Heartbeats: the configuration's before Welcome, the master's after.
  std::uint32_t heartbeat_ms() const { return heartbeat_ms_; }
  /// Silence after which the master counts as gone: the connect timeout
  /// before Welcome, silence_limit_ms(heartbeat_ms()) after (cluster_config.h).
  double silence_limit_ms() const;

  /// What to do at a heartbeat tick, with bytes last received from the master at `last_received`.
  enum class Tick {
    wait,            ///< before Welcome, the master not silent for too long
    send_heartbeat,  ///< after Welcome, the master alive
    master_gone,     ///< nothing received for silence_limit_ms(): close, exit kNodeExitMasterLost
  };
  Tick tick(Clock::time_point last_received, Clock::time_point now) const;

 private:
  SharedSecret secret_;
  std::string cluster_name_, node_name_;
  std::uint32_t heartbeat_ms_;
  std::uint32_t connect_timeout_ms_;
  std::optional<NodeHandshake> handshake_;
  bool welcomed_ = false;
};

}  // namespace zenith::cluster
