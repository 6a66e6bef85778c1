#pragma once
// A node's side of a link check (`zenith cluster check`; docs/cluster.md,
// "Checking the network"): a LinkCheck opens a window of fast pings (the
// node's MasterDatagrams counts them), then the master's LinkFill bytes
// arrive — their first and last arrival time the throughput — and once both
// are over the node answers with a LinkReport of what it measured. Pure
// bookkeeping: times are passed in.
#include <chrono>
#include <cstdint>
#include <optional>

#include "cluster/link/clock_sync.h"
#include "cluster/link/ping_probe.h"
#include "cluster/protocol/messages.h"

namespace zenith::cluster {

class LinkCheckAnswer {
 public:
  using Clock = std::chrono::steady_clock;

  /// A LinkCheck arrived at `now`: pings from now for its duration (or until
  /// the first LinkFill), then its fill. A check under way starts afresh.
  void start(const LinkCheck& check, Clock::time_point now);
  /// Whether a check is under way (started, its report not yet taken).
  bool running() const { return check_.has_value(); }
  /// When the pings' window ends (the check's duration, or the first fill's arrival).
  Clock::time_point pings_until() const { return pings_until_; }
  /// A LinkFill at `now`. Throws std::runtime_error naming what is wrong: no
  /// check under way, an index out of order, more bytes than the check named.
  void on_fill(const LinkFill& fill, Clock::time_point now);
  /// Whether the report is due at `now`: the pings' window is over and every fill byte came.
  bool complete(Clock::time_point now) const;
  /// The report of the check (its pings, the node's clock estimate at
  /// `node_steady_ns`, when the wall clock read `node_wall_ns`); the check ends.
  LinkReport report(const PingProbe::Summary& pings, const ClockSync& clock, std::int64_t node_steady_ns,
                    std::uint64_t node_wall_ns);

 private:
  std::optional<LinkCheck> check_;
  Clock::time_point pings_until_{};
  std::uint64_t fill_bytes_ = 0, timed_bytes_ = 0;
  std::uint32_t next_index_ = 0;
  Clock::time_point first_fill_{}, last_fill_{};
};

}  // namespace zenith::cluster
