#include "cluster/link/ping_probe.h"

#include <algorithm>
#include <cmath>

namespace zenith::cluster {

void PingProbe::sent(std::uint64_t node_sent_ns) {
  if (pings_.empty()) first_ = node_sent_ns;
  first_ = std::min(first_, node_sent_ns);
  last_ = std::max(last_, node_sent_ns);
  pings_.emplace(node_sent_ns, false);
}

bool PingProbe::answered(std::uint64_t node_sent_ns, std::uint64_t round_trip_ns) {
  const auto ping = pings_.find(node_sent_ns);
  if (ping == pings_.end() || ping->second) return false;
  ping->second = true;
  round_trips_ns_.push_back(round_trip_ns);
  return true;
}

PingProbe::Summary PingProbe::summary() const {
  Summary s;
  s.pings = static_cast<std::uint32_t>(pings_.size());
  s.pongs = static_cast<std::uint32_t>(round_trips_ns_.size());
  s.first_ping_ns = first_;
  s.last_ping_ns = last_;
  if (round_trips_ns_.empty()) return s;
  std::vector<std::uint64_t> sorted = round_trips_ns_;
  std::sort(sorted.begin(), sorted.end());
  // The nearest-rank percentile: the smallest sample with at least p of them at or below it.
  const auto rank = [&](double p) {
    const auto k = static_cast<std::size_t>(std::ceil(p * static_cast<double>(sorted.size())));
    return sorted[std::clamp<std::size_t>(k, 1, sorted.size()) - 1];
  };
  s.round_trip_min_ns = sorted.front();
  s.round_trip_p50_ns = rank(0.50);
  s.round_trip_p99_ns = rank(0.99);
  s.round_trip_max_ns = sorted.back();
  return s;
}

}  // namespace zenith::cluster
