#include "show/playback_clock.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace zenith::show {
namespace {

TEST(PlaybackClock, PlaysFrameByFrameAndFinishesAtTheEnd) {
  PlaybackClock clock(1.0, 4.0, false);
  EXPECT_TRUE(clock.playing());
  EXPECT_EQ(clock.next_frame_time_s(), 0.0);
  EXPECT_EQ(clock.next_frame_time_s(), 0.25);
  EXPECT_EQ(clock.next_frame_time_s(), 0.5);
  EXPECT_EQ(clock.next_frame_time_s(), 0.75);
  EXPECT_FALSE(clock.finished());
  EXPECT_EQ(clock.next_frame_time_s(), 1.0);  // the end itself is shown
  EXPECT_TRUE(clock.finished());
  EXPECT_EQ(clock.next_frame_time_s(), 1.0);  // and held
  EXPECT_EQ(clock.status(), "finished at 1.000 s of 1.000 s, rate 1, loop off");
}

TEST(PlaybackClock, NeverStepsOverTheEnd) {
  PlaybackClock clock(1.1, 2.0, false);
  EXPECT_EQ(clock.next_frame_time_s(), 0.0);
  EXPECT_EQ(clock.next_frame_time_s(), 0.5);
  EXPECT_EQ(clock.next_frame_time_s(), 1.0);
  EXPECT_EQ(clock.next_frame_time_s(), 1.1);
  EXPECT_TRUE(clock.finished());
}

TEST(PlaybackClock, LoopsBackToTheStart) {
  PlaybackClock clock(0.5, 4.0, true);
  const double expected[] = {0.0, 0.25, 0.5, 0.0, 0.25, 0.5, 0.0};
  for (double t : expected) EXPECT_EQ(clock.next_frame_time_s(), t);
  EXPECT_FALSE(clock.finished());
}

TEST(PlaybackClock, PauseHoldsAndPlayResumes) {
  PlaybackClock clock(10.0, 10.0, false);
  clock.next_frame_time_s();
  clock.pause();
  EXPECT_EQ(clock.next_frame_time_s(), 0.1);
  EXPECT_EQ(clock.next_frame_time_s(), 0.1);
  clock.play();
  EXPECT_EQ(clock.next_frame_time_s(), 0.1);
  EXPECT_DOUBLE_EQ(clock.next_frame_time_s(), 0.2);
}

TEST(PlaybackClock, SeekClampsAndShowsTheTargetNext) {
  PlaybackClock clock(10.0, 10.0, false);
  clock.seek(4.5);
  EXPECT_EQ(clock.next_frame_time_s(), 4.5);
  clock.seek(99.0);
  EXPECT_EQ(clock.time_s(), 10.0);
  clock.seek(-3.0);
  EXPECT_EQ(clock.time_s(), 0.0);
  EXPECT_THROW(clock.seek(std::nan("")), std::invalid_argument);
}

TEST(PlaybackClock, ReverseRunsToTheStart) {
  PlaybackClock clock(1.0, 2.0, false);
  clock.seek(1.0);
  clock.set_rate(-1.0);
  EXPECT_EQ(clock.next_frame_time_s(), 1.0);
  EXPECT_EQ(clock.next_frame_time_s(), 0.5);
  EXPECT_EQ(clock.next_frame_time_s(), 0.0);
  EXPECT_TRUE(clock.finished());
  clock.set_loop(true);
  EXPECT_FALSE(clock.finished());
  EXPECT_EQ(clock.next_frame_time_s(), 0.0);
  EXPECT_EQ(clock.next_frame_time_s(), 1.0);  // reversed loops wrap to the end
}

TEST(PlaybackClock, RateScalesTheStepAndIsBounded) {
  PlaybackClock clock(100.0, 10.0, false);
  clock.set_rate(2.5);
  clock.next_frame_time_s();
  EXPECT_DOUBLE_EQ(clock.next_frame_time_s(), 0.25);
  EXPECT_THROW(clock.set_rate(16.5), std::invalid_argument);
  EXPECT_THROW(clock.set_rate(-17.0), std::invalid_argument);
  EXPECT_EQ(clock.rate(), 2.5);
  clock.set_rate(0.0);
  const double held = clock.next_frame_time_s();
  EXPECT_EQ(clock.next_frame_time_s(), held);
}

TEST(PlaybackClock, PlayAfterFinishingStartsOver) {
  PlaybackClock clock(0.0, 30.0, false);
  EXPECT_EQ(clock.next_frame_time_s(), 0.0);
  EXPECT_EQ(clock.next_frame_time_s(), 0.0);
  EXPECT_TRUE(clock.finished());
  PlaybackClock other(1.0, 1.0, false);
  other.next_frame_time_s();
  other.next_frame_time_s();
  other.next_frame_time_s();
  EXPECT_TRUE(other.finished());
  other.play();
  EXPECT_FALSE(other.finished());
  EXPECT_EQ(other.next_frame_time_s(), 0.0);
}

TEST(PlaybackClock, RejectsBadConstruction) {
  EXPECT_THROW(PlaybackClock(-1.0, 30.0, false), std::invalid_argument);
  EXPECT_THROW(PlaybackClock(1.0, 0.0, false), std::invalid_argument);
  EXPECT_THROW(PlaybackClock(1.0, 1001.0, false), std::invalid_argument);
}

TEST(PlaybackClock, AppliesOperatorCommands) {
  PlaybackClock clock(60.0, 30.0, false);
  EXPECT_EQ(clock.apply_command("pause"), "paused at 0.000 s of 60.000 s, rate 1, loop off");
  EXPECT_EQ(clock.apply_command("  seek   12.5 "), "paused at 12.500 s of 60.000 s, rate 1, loop off");
  EXPECT_EQ(clock.apply_command("toggle"), "playing at 12.500 s of 60.000 s, rate 1, loop off");
  EXPECT_EQ(clock.apply_command("rate -2"), "playing at 12.500 s of 60.000 s, rate -2, loop off");
  EXPECT_EQ(clock.apply_command("loop on"), "playing at 12.500 s of 60.000 s, rate -2, loop on");
  EXPECT_EQ(clock.apply_command("toggle"), "paused at 12.500 s of 60.000 s, rate -2, loop on");
  EXPECT_EQ(clock.apply_command("play"), "playing at 12.500 s of 60.000 s, rate -2, loop on");
  EXPECT_EQ(clock.apply_command("status"), clock.status());
}

TEST(PlaybackClock, RejectsMalformedCommandsWithUsage) {
  PlaybackClock clock(60.0, 30.0, false);
  for (const char* bad : {"", "jump", "seek", "seek ten", "seek 1 2", "rate 20", "rate", "loop maybe", "play now",
                          "seek 1e999", "rate nan"}) {
    try {
      clock.apply_command(bad);
      ADD_FAILURE() << "accepted \"" << bad << "\"";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("commands: play | pause | toggle | seek SECONDS"), std::string::npos) << bad;
    }
  }
  EXPECT_EQ(clock.time_s(), 0.0);
  EXPECT_EQ(clock.rate(), 1.0);
}

}  // namespace
}  // namespace zenith::show
