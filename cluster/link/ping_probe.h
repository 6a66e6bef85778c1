#pragma once
// The pings of a link check (docs/cluster.md, "Checking the network"), as the
// node counts them: every ClockPing it sent, the distinct ClockPongs that
// answered them, and their round trips. A pong is matched to its ping by the
// ping's stamp (t1, echoed in the pong): a duplicated datagram, a pong of a
// ping sent before the check, or one that names no ping counts nothing.
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace zenith::cluster {

class PingProbe {
 public:
  /// What the probe measured (all ns; the round trips 0 without a pong).
  struct Summary {
    std::uint32_t pings = 0, pongs = 0;
    std::uint64_t first_ping_ns = 0, last_ping_ns = 0;
    std::uint64_t round_trip_min_ns = 0, round_trip_p50_ns = 0, round_trip_p99_ns = 0, round_trip_max_ns = 0;
  };

  /// A ping left at the node's `node_sent_ns` (t1; distinct per ping).
  void sent(std::uint64_t node_sent_ns);
  /// A pong echoed `node_sent_ns`, with the exchange's round trip δ (≥ 0).
  /// Returns whether it answered a ping of this probe not answered before.
  bool answered(std::uint64_t node_sent_ns, std::uint64_t round_trip_ns);
  Summary summary() const;

 private:
  std::unordered_map<std::uint64_t, bool> pings_;  ///< t1 → answered
  std::vector<std::uint64_t> round_trips_ns_;
  std::uint64_t first_ = 0, last_ = 0;
};

}  // namespace zenith::cluster
