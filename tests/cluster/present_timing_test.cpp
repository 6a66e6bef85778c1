// How a node's render thread meets a scheduled frame's moment (cluster/node/present_timing.h).
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <chrono>
#include <thread>

#include "cluster/node/present_timing.h"

namespace zenith::cluster {
namespace {

using Clock = std::chrono::steady_clock;

struct Policy {
  int policy = -1;  ///< without SCHED_RESET_ON_FORK
  int priority = -1;
};
Policy this_threads_policy() {
  Policy p;
  sched_param param{};
  p.policy = sched_getscheduler(0) & ~SCHED_RESET_ON_FORK;
  sched_getparam(0, &param);
  p.priority = param.sched_priority;
  return p;
}

TEST(PresentTiming, TheSleepEndsAtTheMomentNotBefore) {
  for (int i = 0; i < 5; ++i) {
    const Clock::time_point moment = Clock::now() + std::chrono::microseconds(1500 + 700 * i);
    sleep_until_moment(moment);
    EXPECT_GE(Clock::now(), moment) << "round " << i;
  }
  const Clock::time_point passed = Clock::now() - std::chrono::seconds(1);
  const Clock::time_point before = Clock::now();
  sleep_until_moment(passed);
  EXPECT_LT(Clock::now() - before, std::chrono::milliseconds(500)) << "a moment that passed does not wait";
}

// Run in a thread of its own, so that the test's thread keeps its policy
// whatever happens. Where the kernel allows SCHED_FIFO (CI runs as root) the
// thread runs it inside the scope only; where it refuses, nothing changes
// and the refusal is remembered (one log line, no second attempt).
TEST(PresentTiming, ThePresentsPriorityIsRealTimeForTheScopeOnlyWhereAllowed) {
  std::thread([] {
    const Policy normal = this_threads_policy();
    ASSERT_EQ(normal.policy, SCHED_OTHER);
    PresentPriority priority(true, "n0");
    EXPECT_TRUE(priority.realtime_possible());
    for (int round = 0; round < 2; ++round) {
      {
        const PresentPriority::Raised raised = priority.raise();
        const Policy inside = this_threads_policy();
        if (raised.realtime()) {
          EXPECT_EQ(inside.policy, SCHED_FIFO);
          EXPECT_EQ(inside.priority, kPresentFifoPriority);
          // A thread started while raised (a driver's worker) runs normally.
          Policy started;
          std::thread([&] { started = this_threads_policy(); }).join();
          EXPECT_EQ(started.policy, SCHED_OTHER);
          EXPECT_EQ(started.priority, 0);
        } else {
          EXPECT_EQ(inside.policy, SCHED_OTHER) << "refused: the thread keeps its policy";
          EXPECT_FALSE(priority.realtime_possible()) << "a refusal is remembered";
        }
      }
      const Policy after = this_threads_policy();
      EXPECT_EQ(after.policy, normal.policy) << "round " << round;
      EXPECT_EQ(after.priority, normal.priority) << "round " << round;
    }
  }).join();
}

TEST(PresentTiming, ANormalPresentPriorityLeavesTheThreadAsItIs) {
  std::thread([] {
    PresentPriority priority(false, "n0");
    EXPECT_FALSE(priority.realtime_possible());
    const PresentPriority::Raised raised = priority.raise();
    EXPECT_FALSE(raised.realtime());
    EXPECT_EQ(this_threads_policy().policy, SCHED_OTHER);
  }).join();
}

}  // namespace
}  // namespace zenith::cluster
