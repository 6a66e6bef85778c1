#pragma once
// The master's liveness rule for node connections (docs/cluster.md, "Join,
// rejoin and failures"), as pure logic: at every heartbeat tick the master
// asks, for each open connection, whether to send it a Heartbeat or to close
// it. No sockets; the caller passes the clock readings.
#include <chrono>
#include <cstdint>

namespace zenith::cluster {

/// Invariants: a connection still in the handshake gets no Heartbeat and is
/// closed only for taking longer than handshake_limit_ms() since it
/// connected; an authenticated one is closed once nothing arrived from it for
/// longer than silence_limit_ms(), and otherwise gets a Heartbeat per tick.
class HeartbeatMonitor {
 public:
  using Clock = std::chrono::steady_clock;

  /// What to do with one connection at this tick.
  enum class Verdict {
    send_heartbeat,      ///< authenticated and alive
    awaiting_handshake,  ///< still in the handshake, within its time: nothing to do
    handshake_overdue,   ///< no handshake within handshake_limit_ms(): close it
    silent,              ///< nothing received for silence_limit_ms(): close it
  };

  explicit HeartbeatMonitor(std::uint32_t heartbeat_interval_ms);

  /// Time between ticks (and Heartbeats).
  std::uint32_t interval_ms() const { return interval_ms_; }
  /// Silence after which an authenticated node counts as gone: max(3 heartbeats, 10 s).
  double silence_limit_ms() const { return silence_limit_ms_; }
  /// Time a connection gets to complete the handshake: max(5 s, 3 heartbeats)
  /// (docs/protocol.md; a peer that has not proved the secret holds a slot no longer).
  double handshake_limit_ms() const { return handshake_limit_ms_; }

  /// The verdict for a connection made at `connected_at` that last received
  /// bytes at `last_received`, `in_handshake` or authenticated, at `now`.
  Verdict check(bool in_handshake, Clock::time_point connected_at, Clock::time_point last_received,
                Clock::time_point now) const;

 private:
  std::uint32_t interval_ms_;
  double silence_limit_ms_;
  double handshake_limit_ms_;
};

}  // namespace zenith::cluster
