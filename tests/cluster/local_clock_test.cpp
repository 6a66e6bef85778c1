// The node's own clock as its clock synchronisation reads it
// (cluster/link/local_clock.h): the steady clock as it is, or a rehearsal of
// a clock that drifts and steps. Readings against the closed form, and the
// inverse (when a timer on the steady clock must fire) against the readings.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <random>

#include "cluster/link/local_clock.h"

namespace zenith::cluster {
namespace {

using Steady = LocalClock::Steady;
using std::chrono::nanoseconds;

constexpr std::int64_t kOrigin = 5'000'000'000;  // the node started 5 s into the steady clock
constexpr std::int64_t kSecond = 1'000'000'000;

Steady::time_point at(std::int64_t ns) { return Steady::time_point(nanoseconds(ns)); }
std::int64_t ns(Steady::time_point t) { return std::chrono::duration_cast<nanoseconds>(t.time_since_epoch()).count(); }

TEST(LocalClock, WithoutFaultsItIsTheSteadyClock) {
  const LocalClock clock;
  EXPECT_EQ(clock.read_ns(at(123'456'789)), 123'456'789);
  EXPECT_EQ(ns(clock.steady_at(987'654'321)), 987'654'321);
  const LocalClock no_faults(LocalClock::Faults{}, at(kOrigin));
  EXPECT_EQ(no_faults.read_ns(at(kOrigin + 7 * kSecond)), kOrigin + 7 * kSecond);
}

TEST(LocalClock, ADriftingClockGainsItsRateAndTimersFindTheirSteadyMoment) {
  const LocalClock clock(LocalClock::Faults{250.0, 0, nanoseconds(0)}, at(kOrigin));
  EXPECT_EQ(clock.read_ns(at(kOrigin)), kOrigin);
  // 250 ppm over 10 s: 2.5 ms ahead; before the origin, as far behind.
  EXPECT_EQ(clock.read_ns(at(kOrigin + 10 * kSecond)), kOrigin + 10 * kSecond + 2'500'000);
  EXPECT_EQ(clock.read_ns(at(kOrigin - 2 * kSecond)), kOrigin - 2 * kSecond - 500'000);
  std::mt19937_64 random(7);
  std::uniform_int_distribution<std::int64_t> moment(0, 3600 * kSecond);
  for (int k = 0; k < 1000; ++k) {
    const std::int64_t s = kOrigin + moment(random);
    // The first steady moment reading at least what s reads is s itself (the clock rises 1.00025 ns a ns).
    EXPECT_EQ(ns(clock.steady_at(clock.read_ns(at(s)))), s) << s;
  }
}

TEST(LocalClock, AStepIsTakenAheadThenBackAtEachInterval) {
  const LocalClock clock(LocalClock::Faults{0.0, 25'000'000, nanoseconds(2 * kSecond)}, at(kOrigin));
  EXPECT_EQ(clock.read_ns(at(kOrigin + 2 * kSecond - 1)), kOrigin + 2 * kSecond - 1);
  EXPECT_EQ(clock.read_ns(at(kOrigin + 2 * kSecond)), kOrigin + 2 * kSecond + 25'000'000);
  EXPECT_EQ(clock.read_ns(at(kOrigin + 3 * kSecond)), kOrigin + 3 * kSecond + 25'000'000);
  EXPECT_EQ(clock.read_ns(at(kOrigin + 4 * kSecond)), kOrigin + 4 * kSecond);
  EXPECT_EQ(clock.read_ns(at(kOrigin + 6 * kSecond + 1)), kOrigin + 6 * kSecond + 1 + 25'000'000);
  // A moment the clock jumped over: a timer waiting for it fires at the jump.
  EXPECT_EQ(ns(clock.steady_at(kOrigin + 2 * kSecond + 10'000'000)), kOrigin + 2 * kSecond);
  // Just after the jump: 25 ms earlier on the steady clock.
  EXPECT_EQ(ns(clock.steady_at(kOrigin + 2 * kSecond + 30'000'000)), kOrigin + 2 * kSecond + 5'000'000);
  // Back at 4 s, the clock reads [4 s, 4 s + 25 ms) twice: the first time counts.
  EXPECT_EQ(ns(clock.steady_at(kOrigin + 4 * kSecond + 10'000'000)), kOrigin + 4 * kSecond - 15'000'000);
}

TEST(LocalClock, ABackwardStepWithDriftStillGivesTheFirstMomentThatReadsTheTime) {
  const LocalClock::Faults faults{-400.0, -40'000'000, nanoseconds(kSecond / 2)};
  const LocalClock clock(faults, at(kOrigin));
  std::mt19937_64 random(11);
  std::uniform_int_distribution<std::int64_t> moment(0, 20 * kSecond);
  for (int k = 0; k < 300; ++k) {
    const std::int64_t local = kOrigin + moment(random);
    const std::int64_t s = ns(clock.steady_at(local));
    EXPECT_GE(clock.read_ns(at(s)), local) << local;
    // Nothing earlier reads it: a brute-force look over the 60 ms before (longer than the 40 ms step back, so
    // a first reading before a jump back would be seen), every 10 µs.
    for (std::int64_t back = 10'000; back <= 60'000'000; back += 10'000)
      ASSERT_LT(clock.read_ns(at(s - back)), local) << local << " read earlier at " << s - back;
  }
}

}  // namespace
}  // namespace zenith::cluster
