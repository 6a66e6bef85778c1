#pragma once
// A node's datagrams with its master (docs/cluster.md, "The frame schedule"
// and "Clocks"; docs/protocol.md, "Datagrams"), on the node's networking
// thread: a UDP socket to the master's port (the same number as its TCP
// port), a ClockPing every kPingInterval — whose ClockPongs feed the node's
// ClockSync and tell the master where to send — and the master's scheduled
// frames (FrameSchedule + FrameState) handed to the node. Datagrams that fail
// their tag, or come from elsewhere, are dropped with a rate-limited line.
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/steady_timer.hpp>

#include "cluster/link/clock_sync.h"
#include "cluster/link/local_clock.h"
#include "cluster/link/ping_probe.h"
#include "cluster/protocol/messages.h"
#include "core/log_limiter.h"

namespace zenith::cluster {

class MasterDatagrams {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kPingInterval{100};
  /// Crystals differ by tens of ppm: a drift beyond this is a clock being slewed hard, or broken (logged once).
  static constexpr double kDriftWarnPpm = 500.0;

  /// A frame the master scheduled, as it arrived in a datagram.
  struct ScheduledFrame {
    FrameSchedule schedule;
    FrameState state;
  };
  using FrameHandler = std::function<void(ScheduledFrame&& frame)>;

  /// `local`: the node's own clock as the clock synchronisation reads it
  /// (the steady clock, unless a rehearsal of clock faults skews it).
  MasterDatagrams(boost::asio::io_context& io, std::string who, FrameHandler on_frame, LocalClock local = {});
  MasterDatagrams(const MasterDatagrams&) = delete;
  MasterDatagrams& operator=(const MasterDatagrams&) = delete;

  /// A welcomed session: datagrams to `master` as node `node_id` under `key`;
  /// the clock estimate starts from the Welcome's `master_time_ns` (received
  /// at `welcomed`). Starts pinging.
  void start(const boost::asio::ip::udp::endpoint& master, std::uint32_t node_id, const Digest& key,
             std::uint64_t master_time_ns, Clock::time_point welcomed);
  /// The session ended: the socket closes; the clock estimate is kept (a
  /// reconnection to the same master goes on from it, the seed of the next
  /// Welcome replaces it otherwise).
  void stop();

  /// A link check (docs/cluster.md, "Checking the network"): a ping every
  /// `interval` from now until `until` (then every kPingInterval again),
  /// each counted in probe() with its pong. A probe started afresh.
  void start_probe(std::chrono::microseconds interval, Clock::time_point until);
  /// Ends the probe's pings now (its counts stay).
  void end_probe();
  const PingProbe& probe() const { return probe_; }

  const ClockSync& clock() const { return clock_; }
  /// The node's own clock, which ClockSync's node times are read on.
  const LocalClock& local_clock() const { return local_; }
  /// The node's steady time at which the master's clock reads `master_ns`
  /// (as far as the node's own clock and its estimate of the offset tell).
  Clock::time_point to_local(std::uint64_t master_ns) const;
  /// When the last valid datagram of the master arrived (nothing before one).
  std::optional<Clock::time_point> last_heard() const { return last_heard_; }

 private:
  void receive();
  void on_datagram(std::size_t bytes);
  void ping();

  boost::asio::io_context& io_;
  std::string who_;
  FrameHandler on_frame_;
  std::optional<boost::asio::ip::udp::socket> socket_;
  boost::asio::ip::udp::endpoint master_, sender_;
  std::uint32_t node_id_ = 0;
  Digest key_{};
  std::uint64_t generation_ = 0;  ///< handlers of an earlier session do nothing
  std::uint64_t ping_chain_ = 0;  ///< a ping timer of an earlier chain (before a probe started) does nothing
  boost::asio::steady_timer ping_timer_;
  std::vector<std::uint8_t> buffer_;
  LocalClock local_;
  ClockSync clock_;
  PingProbe probe_;
  std::chrono::microseconds probe_interval_{0};
  Clock::time_point probe_until_{};
  std::optional<Clock::time_point> last_heard_;
  core::LogLimiter refused_;
  bool synchronized_logged_ = false;
  std::uint64_t steps_logged_ = 0;  ///< clock steps already logged
  bool drift_logged_ = false;       ///< a drift beyond kDriftWarnPpm logged
};

}  // namespace zenith::cluster
