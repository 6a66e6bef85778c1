// When a node renders and presents scheduled frames (cluster/node/present_schedule.h).
#include <gtest/gtest.h>

#include <chrono>

#include "cluster/node/present_schedule.h"

namespace zenith::cluster {
namespace {

using Clock = PresentSchedule::Clock;
using Kind = PresentSchedule::Step::Kind;
using std::chrono::milliseconds;

const Clock::time_point t0 = Clock::time_point() + std::chrono::hours(1);
Clock::time_point at_ms(double ms) { return t0 + std::chrono::microseconds(static_cast<long long>(ms * 1000)); }
FrameState frame(std::uint64_t n) {
  FrameState f;
  f.frame = n;
  return f;
}
/// Frame n due at n · 16 ms.
Clock::time_point due(std::uint64_t n) { return at_ms(16.0 * static_cast<double>(n)); }

TEST(PresentSchedule, RendersOneFrameAheadAndPresentsEachAtItsMoment) {
  PresentSchedule s;
  for (std::uint64_t n = 1; n <= 3; ++n)
    EXPECT_EQ(s.on_frame(frame(n), due(n), at_ms(0)), PresentSchedule::Arrival::taken);
  auto step = s.next(at_ms(0));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->kind, Kind::render);
  EXPECT_EQ(step->frame, 1u);
  EXPECT_FALSE(s.next(at_ms(1))) << "frame 2 waits until frame 1 is on the screen";
  EXPECT_EQ(s.wake_at(), due(1));
  for (std::uint64_t n = 1; n <= 3; ++n) {
    step = s.next(due(n));
    ASSERT_TRUE(step);
    EXPECT_EQ(step->kind, Kind::present);
    EXPECT_EQ(step->frame, n);
    if (n < 3) {
      step = s.next(due(n));
      ASSERT_TRUE(step);
      EXPECT_EQ(step->kind, Kind::render);
      EXPECT_EQ(step->frame, n + 1);
    }
  }
  EXPECT_FALSE(s.next(due(3)));
  EXPECT_EQ(s.presented(), 3u);
  EXPECT_EQ(s.missed(), 0u);
}

TEST(PresentSchedule, CopiesOlderFramesAndLateFramesAreRefused) {
  PresentSchedule s;
  EXPECT_EQ(s.on_frame(frame(5), due(5), at_ms(0)), PresentSchedule::Arrival::taken);
  EXPECT_EQ(s.on_frame(frame(5), due(5), at_ms(1)), PresentSchedule::Arrival::duplicate);
  ASSERT_TRUE(s.next(at_ms(1)));  // render 5
  EXPECT_EQ(s.on_frame(frame(5), due(5), at_ms(2)), PresentSchedule::Arrival::duplicate);
  ASSERT_EQ(s.next(due(5))->kind, Kind::present);
  EXPECT_EQ(s.on_frame(frame(4), due(6), due(5)), PresentSchedule::Arrival::stale);
  EXPECT_EQ(s.on_frame(frame(6), due(6), due(6)), PresentSchedule::Arrival::late);
}

// Frame 23's first two copies were lost; its last copy arrives just after the
// node moved on to frame 24 at frame 22's moment. It is still in time: it goes
// first, and frame 24 is rendered again after it. No frame is missed.
TEST(PresentSchedule, AnEarlierFrameStillInTimeGoesBeforeTheCurrentOne) {
  PresentSchedule s;
  s.on_frame(frame(22), due(22), at_ms(300));
  ASSERT_EQ(s.next(at_ms(300))->frame, 22u);
  s.on_frame(frame(24), due(24), at_ms(330));
  ASSERT_EQ(s.next(due(22))->kind, Kind::present);
  auto step = s.next(due(22));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->frame, 24u);  // 23 is not there yet
  EXPECT_EQ(s.on_frame(frame(23), due(23), due(22) + milliseconds(1)), PresentSchedule::Arrival::taken);
  step = s.next(due(22) + milliseconds(1));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->kind, Kind::render);
  EXPECT_EQ(step->frame, 23u);
  ASSERT_EQ(s.next(due(23))->frame, 23u);  // presented
  step = s.next(due(23));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->kind, Kind::render);
  EXPECT_EQ(step->frame, 24u);  // rendered again
  ASSERT_EQ(s.next(due(24))->kind, Kind::present);
  EXPECT_EQ(s.missed(), 0u);
  EXPECT_EQ(s.presented(), 3u);
}

// A node cut off for a while: the frames that came back after their moment
// are dropped, the first one still ahead is shown on time, and the gap is
// counted as missed.
TEST(PresentSchedule, AfterACutTheNextFrameStillAheadIsShownOnTime) {
  PresentSchedule s;
  s.on_frame(frame(1), due(1), at_ms(0));
  ASSERT_EQ(s.next(at_ms(0))->kind, Kind::render);
  ASSERT_EQ(s.next(due(1))->kind, Kind::present);
  // Frames 2..9 never came; 10..13 arrive at 150 ms (10 is due at 160).
  for (std::uint64_t n = 10; n <= 13; ++n) s.on_frame(frame(n), due(n), at_ms(150));
  auto step = s.next(at_ms(150));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->frame, 10u);
  step = s.next(due(10));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->kind, Kind::present);
  EXPECT_EQ(s.missed(), 8u);
}

// A frame whose moment passes while it waits (the node rendered too slowly) is
// dropped; the next one due is rendered instead.
TEST(PresentSchedule, FramesWhoseMomentPassedWhileWaitingAreSkipped) {
  PresentSchedule s;
  for (std::uint64_t n = 1; n <= 4; ++n) s.on_frame(frame(n), due(n), at_ms(0));
  ASSERT_EQ(s.next(at_ms(0))->frame, 1u);
  // The node comes back only at 40 ms (frame 1's present ran late).
  auto step = s.next(at_ms(40));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->kind, Kind::present);
  EXPECT_EQ(step->frame, 1u);
  step = s.next(at_ms(40));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->kind, Kind::render);
  EXPECT_EQ(step->frame, 3u) << "frame 2 was due at 32 ms";
  ASSERT_EQ(s.next(due(3))->frame, 3u);
  EXPECT_EQ(s.missed(), 1u);
}

// The render thread, about to render a frame while a later one waits behind it
// (the frame before took longer than a period on a busy machine): on a
// schedule it renders it, late, while the later frame's moment is ahead, and
// drops it once that moment has come; under the barrier it always drops it.
TEST(PresentSchedule, ARenderThatFellBehindDropsAFrameOnlyOnceTheNextIsDue) {
  // Frame 2 is about to be rendered at 33 ms, 1 ms after its moment; frame 3 is due at 48 ms.
  EXPECT_FALSE(drop_frame_behind(due(3), at_ms(33))) << "15 ms left: frame 2 shown late, frame 3 on time";
  EXPECT_FALSE(drop_frame_behind(due(3), at_ms(47.9)));
  EXPECT_TRUE(drop_frame_behind(due(3), due(3))) << "frame 3 is due: frame 2 would follow it";
  EXPECT_TRUE(drop_frame_behind(due(3), at_ms(60)));
  EXPECT_TRUE(drop_frame_behind(std::nullopt, at_ms(0))) << "the barrier: the master moved on";
}

// The present is handed to the render thread `handoff` before its moment
// (it waits for the moment itself); the next frame is made current with it,
// and frames are still dropped only once their true moment has passed.
TEST(PresentSchedule, APresentIsHandedOutItsHandoffBeforeItsMoment) {
  PresentSchedule s(milliseconds(4));
  for (std::uint64_t n = 1; n <= 3; ++n) s.on_frame(frame(n), due(n), at_ms(0));
  ASSERT_EQ(s.next(at_ms(0))->frame, 1u);
  EXPECT_EQ(s.wake_at(), due(1) - milliseconds(4));
  EXPECT_FALSE(s.next(at_ms(11.9))) << "more than 4 ms before frame 1's moment";
  auto step = s.next(at_ms(12));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->kind, Kind::present);
  EXPECT_EQ(step->frame, 1u);
  EXPECT_EQ(step->present_at, due(1)) << "the step carries the moment the render thread waits for";
  step = s.next(at_ms(12));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->kind, Kind::render);
  EXPECT_EQ(step->frame, 2u);
  // The node wakes late, 1 ms before frame 3's moment: frame 2 is presented
  // (late), and frame 3, still ahead, rendered — not dropped for being inside the handoff.
  step = s.next(due(3) - milliseconds(1));
  ASSERT_EQ(step->kind, Kind::present);
  EXPECT_EQ(step->frame, 2u);
  step = s.next(due(3) - milliseconds(1));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->kind, Kind::render);
  EXPECT_EQ(step->frame, 3u);
  EXPECT_EQ(s.missed(), 0u);
}

TEST(PresentSchedule, TheHandoffIsFourMillisecondsAtMostHalfAPeriod) {
  EXPECT_EQ(present_handoff(30.0), milliseconds(4));
  EXPECT_EQ(present_handoff(60.0), milliseconds(4));
  EXPECT_EQ(present_handoff(125.0), milliseconds(4));
  using Ms = std::chrono::duration<double, std::milli>;
  EXPECT_NEAR(Ms(present_handoff(240.0)).count(), 1000.0 / 480.0, 1e-6);
}

}  // namespace
}  // namespace zenith::cluster
