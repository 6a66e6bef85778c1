// When the master starts each frame (cluster/master/frame_pacer.h): the
// schedule at the display's rate, waits for tables, falling behind.
#include "cluster/master/frame_pacer.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace zenith::cluster {
namespace {

using namespace std::chrono;
using Clock = FramePacer::Clock;

double ms(Clock::duration d) { return duration<double, std::milli>(d).count(); }

TEST(FramePacer, FramesAreDueAtTheRateWithoutDrift) {
  for (const double hz : {60.0, 120.0, 240.0}) {
    FramePacer pacer(hz);
    const Clock::time_point t0 = Clock::now();
    pacer.start(t0);
    EXPECT_EQ(pacer.due(0), t0);
    EXPECT_NEAR(ms(pacer.due(1) - t0), 1000.0 / hz, 1e-6);
    // An hour of frames: n / rate, not n rounded periods (no drift of a tick a frame).
    const std::uint64_t n = static_cast<std::uint64_t>(3600 * hz);
    EXPECT_NEAR(ms(pacer.due(n) - t0), 3.6e6, 1e-3) << hz << " Hz";
  }
}

/// The warm-up frame (frame 0: the nodes' programs, buffers, uploads and
/// first swap) may take many periods: it is never late, it moves nothing,
/// and the schedule starts at its Present (the master calls start() then).
TEST(FramePacer, TheWarmUpFrameIsNeverLateAndTheScheduleStartsAtItsPresent) {
  FramePacer pacer(60.0);
  const double period_ms = 1000.0 / 60.0;
  const Clock::time_point sent = Clock::now();
  const Clock::time_point presented = sent + milliseconds(850);  // 51 periods of warm-up
  EXPECT_FALSE(pacer.late(0, presented));
  pacer.start(presented);
  // Frame 1 a whole period after the warm-up frame's Present, not at once, and no slip.
  EXPECT_NEAR(ms(pacer.wait_before(1, presented)), period_ms, 1e-6);
  EXPECT_EQ(pacer.slips(), 0u);
  // The first paced frame is late only more than a period after it was due.
  EXPECT_FALSE(pacer.late(1, pacer.due(1) + microseconds(16600)));
  EXPECT_TRUE(pacer.late(1, pacer.due(1) + microseconds(16700)));
  EXPECT_FALSE(pacer.late(2, pacer.due(2)));
  EXPECT_NEAR(ms(pacer.due(2) - presented), 2.0 * period_ms, 1e-6);
}

TEST(FramePacer, WaitsUntilAFrameIsDueAndNeverBeforeIt) {
  FramePacer pacer(60.0);
  const Clock::time_point t0 = Clock::now();
  pacer.start(t0);
  // Frame 1 asked for 5 ms after frame 0: it waits the rest of the 16.7 ms period.
  EXPECT_NEAR(ms(pacer.wait_before(1, t0 + milliseconds(5))), 1000.0 / 60.0 - 5.0, 1e-6);
  // A little late (less than a period): at once, and the schedule stays (the next one catches up).
  EXPECT_EQ(pacer.wait_before(2, pacer.due(2) + milliseconds(10)), Clock::duration::zero());
  EXPECT_EQ(pacer.slips(), 0u);
  EXPECT_NEAR(ms(pacer.due(3) - t0), 50.0, 1e-6);
}

TEST(FramePacer, MovesTheScheduleInsteadOfBurstingWhenAPeriodBehind) {
  FramePacer pacer(60.0);
  const Clock::time_point t0 = Clock::now();
  pacer.start(t0);
  // Frame 10 can only start 100 ms after it was due (a slow node): at once, and
  // frame 11 a full period later, not at once too.
  const Clock::time_point late = pacer.due(10) + milliseconds(100);
  EXPECT_EQ(pacer.wait_before(10, late), Clock::duration::zero());
  EXPECT_EQ(pacer.slips(), 1u);
  EXPECT_NEAR(ms(pacer.due(10) - late), 0.0, 1e-3);
  EXPECT_NEAR(ms(pacer.wait_before(11, late)), 1000.0 / 60.0, 1e-3);
}

TEST(FramePacer, AWaitForTablesShiftsTheLaterFrames) {
  FramePacer pacer(30.0);
  const Clock::time_point t0 = Clock::now();
  pacer.start(t0);
  pacer.hold(seconds(4));
  EXPECT_NEAR(ms(pacer.due(3) - t0), 4100.0, 1e-3);
  EXPECT_EQ(pacer.slips(), 0u);
}

TEST(FramePacer, RefusesARateThatIsNotPositive) {
  EXPECT_THROW(FramePacer(0.0), std::invalid_argument);
  EXPECT_THROW(FramePacer(-60.0), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::cluster
