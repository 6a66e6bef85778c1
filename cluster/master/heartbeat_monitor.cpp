#include "cluster/master/heartbeat_monitor.h"

#include <algorithm>

#include "cluster/link/cluster_config.h"

namespace zenith::cluster {

namespace {

double ms_between(HeartbeatMonitor::Clock::time_point from, HeartbeatMonitor::Clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

}  // namespace

HeartbeatMonitor::HeartbeatMonitor(std::uint32_t heartbeat_interval_ms)
    : interval_ms_(heartbeat_interval_ms),
      silence_limit_ms_(cluster::silence_limit_ms(heartbeat_interval_ms)),
      handshake_limit_ms_(std::max(5000.0, 3.0 * heartbeat_interval_ms)) {}

HeartbeatMonitor::Verdict HeartbeatMonitor::check(bool in_handshake, Clock::time_point connected_at,
                                                  Clock::time_point last_received, Clock::time_point now) const {
  if (in_handshake)
    return ms_between(connected_at, now) > handshake_limit_ms_ ? Verdict::handshake_overdue
                                                               : Verdict::awaiting_handshake;
  if (ms_between(last_received, now) > silence_limit_ms_) return Verdict::silent;
  return Verdict::send_heartbeat;
}

}  // namespace zenith::cluster
