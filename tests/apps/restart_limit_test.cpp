// `zenith cluster --restart-nodes`: which deaths restart a node and how often
// (cluster/launcher/restart_limit.h; docs/cluster.md, "Join, rejoin and failures").
#include "cluster/launcher/restart_limit.h"

#include <gtest/gtest.h>

#include <csignal>

namespace zenith::app {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
const RestartLimit::Clock::time_point t0 = RestartLimit::Clock::now();

TEST(RestartLimit, EveryDeathButACleanExitRestarts) {
  EXPECT_FALSE(RestartLimit::died(0)) << "the master's Goodbye, or a SIGTERM the node obeyed";
  EXPECT_TRUE(RestartLimit::died(1)) << "render or write failure";
  EXPECT_TRUE(RestartLimit::died(3)) << "gave up reconnecting";
  EXPECT_TRUE(RestartLimit::died(128 + SIGKILL));
  EXPECT_TRUE(RestartLimit::died(128 + SIGSEGV));
}

TEST(RestartLimit, ACrashLoopStopsAtTheLimitForGood) {
  RestartLimit limit(3, seconds(60));
  EXPECT_TRUE(limit.allow(t0));
  EXPECT_TRUE(limit.allow(t0 + milliseconds(500)));
  EXPECT_TRUE(limit.allow(t0 + seconds(1)));
  EXPECT_EQ(limit.recent(t0 + seconds(1)), 3u);
  EXPECT_FALSE(limit.allow(t0 + seconds(2))) << "a fourth death within 60 s";
  EXPECT_TRUE(limit.gave_up());
  EXPECT_FALSE(limit.allow(t0 + seconds(600))) << "once given up, the node stays down";
  EXPECT_EQ(limit.total(), 3u);
}

TEST(RestartLimit, DeathsFartherApartThanTheWindowAlwaysRestart) {
  RestartLimit limit(2, seconds(60));
  for (int i = 0; i < 20; ++i) EXPECT_TRUE(limit.allow(t0 + seconds(31 * i))) << i;
  EXPECT_FALSE(limit.gave_up());
  EXPECT_EQ(limit.total(), 20u);
  // The window slides: two in 60 s are allowed, the third inside the same 60 s is not.
  RestartLimit sliding(2, seconds(60));
  EXPECT_TRUE(sliding.allow(t0));
  EXPECT_TRUE(sliding.allow(t0 + seconds(59)));
  EXPECT_TRUE(sliding.allow(t0 + seconds(60))) << "the first left the window";
  EXPECT_FALSE(sliding.allow(t0 + seconds(61)));
}

TEST(RestartLimit, NonsenseLimitsAreRefused) {
  EXPECT_THROW(RestartLimit(0, seconds(60)), std::invalid_argument);
  EXPECT_THROW(RestartLimit(1, milliseconds(0)), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::app
