// How a node's render thread meets a scheduled frame's moment (cluster/node/present_timing.h).
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <algorithm>
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

using std::chrono::microseconds;

TEST(PresentTiming, TheWakeMarginIsTheLatestRecentWakeUpWithHeadroomWithinItsBounds) {
  WakeMargin margin(microseconds(2000));
  EXPECT_EQ(margin.margin(), microseconds(2000)) << "before any wake-up: the most it may be";
  margin.record(microseconds(30));
  EXPECT_EQ(margin.margin(), WakeMargin::kSmallest) << "30 us + 100 us of headroom is under the smallest";
  margin.record(microseconds(700));
  margin.record(microseconds(40));
  EXPECT_EQ(margin.margin(), microseconds(800)) << "the latest of the window, 700 us, + 100 us";
  margin.record(microseconds(9000));
  EXPECT_EQ(margin.margin(), microseconds(2000)) << "a stall of the machine: held to the largest";
  margin.record(microseconds(-50));
  // The stall leaves the window kWindow wake-ups after it, the 700 us one before it.
  for (std::size_t i = 0; i + 2 < WakeMargin::kWindow; ++i) margin.record(microseconds(60));
  EXPECT_EQ(margin.margin(), microseconds(2000)) << "the stall is the oldest wake-up the window holds";
  margin.record(microseconds(60));
  EXPECT_EQ(margin.margin(), WakeMargin::kSmallest) << "the window holds only prompt wake-ups now";
  EXPECT_EQ(WakeMargin(microseconds(100)).margin(), WakeMargin::kSmallest) << "never below the smallest";
}

TEST(PresentTiming, TheWaitWakesBeforeTheMomentByTheMarginAndEndsAtTheMoment) {
  WakeMargin margin(microseconds(1500));
  for (int i = 0; i < 5; ++i) {
    const WakeMargin::Duration before = margin.margin();
    const Clock::time_point moment = Clock::now() + microseconds(3000 + 500 * i);
    const MomentWake wake = wait_for_moment(moment, margin);
    const Clock::time_point after = Clock::now();
    EXPECT_GE(after, moment) << "round " << i;
    EXPECT_EQ(moment - wake.asked, before) << "it asked to wake the margin before the moment, round " << i;
    EXPECT_GE(wake.woke, wake.asked) << "round " << i;
    EXPECT_EQ(margin.margin(), std::clamp(wake.woke - wake.asked + WakeMargin::kHeadroom, WakeMargin::kSmallest,
                                          WakeMargin::Duration(microseconds(1500))))
        << "the wake-up is recorded, round " << i;
    margin = WakeMargin(microseconds(1500));
  }
  const Clock::time_point before = Clock::now();
  const MomentWake passed = wait_for_moment(before - std::chrono::seconds(1), margin);
  EXPECT_LT(Clock::now() - before, std::chrono::milliseconds(500)) << "a moment that passed does not wait";
  EXPECT_GE(passed.woke, before);
  EXPECT_EQ(margin.margin(), microseconds(1500)) << "no sleep, nothing recorded";
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
