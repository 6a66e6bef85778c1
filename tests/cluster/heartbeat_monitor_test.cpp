// The master's liveness rule without sockets (cluster/master/heartbeat_monitor.h;
// docs/cluster.md, "Join, rejoin and failures").
#include "cluster/master/heartbeat_monitor.h"

#include <gtest/gtest.h>

#include "cluster/protocol/heartbeat.h"

namespace zenith::cluster {
namespace {

using Verdict = HeartbeatMonitor::Verdict;
using std::chrono::milliseconds;

const HeartbeatMonitor::Clock::time_point t0 = HeartbeatMonitor::Clock::now();

TEST(HeartbeatMonitor, LimitsAreThreeHeartbeatsButAtLeastTenSecondsAndFiveForTheHandshake) {
  const HeartbeatMonitor fast(250);
  EXPECT_EQ(fast.interval_ms(), 250u);
  EXPECT_DOUBLE_EQ(fast.silence_limit_ms(), 10000.0);
  EXPECT_DOUBLE_EQ(fast.handshake_limit_ms(), 5000.0) << "docs/protocol.md: max(5 s, 3 heartbeats)";
  const HeartbeatMonitor slow(5000);
  EXPECT_DOUBLE_EQ(slow.silence_limit_ms(), 15000.0);
  EXPECT_DOUBLE_EQ(slow.handshake_limit_ms(), 15000.0);
}

TEST(HeartbeatMonitor, AnAuthenticatedNodeGetsHeartbeatsUntilItFallsSilent) {
  const HeartbeatMonitor monitor(250);
  EXPECT_EQ(monitor.check(false, t0, t0, t0), Verdict::send_heartbeat);
  EXPECT_EQ(monitor.check(false, t0, t0, t0 + milliseconds(10000)), Verdict::send_heartbeat);
  EXPECT_EQ(monitor.check(false, t0, t0, t0 + milliseconds(10001)), Verdict::silent);
  EXPECT_EQ(monitor.check(false, t0, t0 + milliseconds(5000), t0 + milliseconds(12000)), Verdict::send_heartbeat)
      << "what counts is the last bytes received, not the connection's age";
}

TEST(HeartbeatMonitor, AConnectionInTheHandshakeGetsNoHeartbeatAndItsOwnLimit) {
  const HeartbeatMonitor monitor(250);
  EXPECT_EQ(monitor.check(true, t0, t0, t0 + milliseconds(5000)), Verdict::awaiting_handshake);
  EXPECT_EQ(monitor.check(true, t0, t0 + milliseconds(4000), t0 + milliseconds(5001)), Verdict::handshake_overdue)
      << "bytes received do not extend the handshake's time";
}

TEST(Heartbeat, CarriesTheSendersSteadyClockInNanoseconds) {
  const auto now = HeartbeatMonitor::Clock::time_point(std::chrono::nanoseconds(123456789));
  EXPECT_EQ(heartbeat_at(now).sent_time_ns, 123456789u);
}

}  // namespace
}  // namespace zenith::cluster
