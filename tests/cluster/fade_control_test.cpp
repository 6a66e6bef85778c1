// The operator's fade as a ramp over frames (cluster/operator/fade_control.h):
// the curve, where a fade starts and lands, colours, blackouts, ranges.
#include "cluster/operator/fade_control.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace zenith::cluster {
namespace {

TEST(FadeCurve, IsSmoothstepClampedToTheUnitInterval) {
  EXPECT_EQ(fade_curve(-1.0), 0.0);
  EXPECT_EQ(fade_curve(0.0), 0.0);
  EXPECT_DOUBLE_EQ(fade_curve(0.25), 0.15625);  // 0.0625 · 2.5
  EXPECT_DOUBLE_EQ(fade_curve(0.5), 0.5);
  EXPECT_DOUBLE_EQ(fade_curve(0.75), 0.84375);  // symmetric: 1 − s(0.25)
  EXPECT_EQ(fade_curve(1.0), 1.0);
  EXPECT_EQ(fade_curve(2.0), 1.0);
  // Slope 0 at both ends: a fade starts and lands without a kink.
  const double h = 1e-6;
  EXPECT_NEAR(fade_curve(h) / h, 0.0, 1e-5);
  EXPECT_NEAR((1.0 - fade_curve(1.0 - h)) / h, 0.0, 1e-5);
}

TEST(FadeControl, FadesToBlackOverTheFramesOfItsDurationAndBack) {
  FadeControl fade(60.0);
  EXPECT_FALSE(fade.active(0));
  EXPECT_EQ(fade.at(5).level, 0.0);
  // 2 s at 60 Hz = 120 frames from frame 100: frame 100 is 1/120 in, frame 219 at the target.
  fade.start(100, 1.0, glm::dvec3(0.0), 2.0);
  EXPECT_EQ(fade.frames(), 120u);
  EXPECT_EQ(fade.at(99).level, 0.0);  // before the fade
  EXPECT_DOUBLE_EQ(fade.at(100).level, fade_curve(1.0 / 120.0));
  EXPECT_DOUBLE_EQ(fade.at(159).level, 0.5);  // u = 60/120: the midpoint
  EXPECT_EQ(fade.at(219).level, 1.0);
  EXPECT_EQ(fade.at(5000).level, 1.0);
  EXPECT_EQ(fade.frames_left(100), 119u);
  EXPECT_EQ(fade.frames_left(219), 0u);
  EXPECT_TRUE(fade.active(219));  // resting on black still decides the frames
  // Back to the picture over 1 s from frame 300: from 1 at the start, the colour kept.
  fade.start(300, 0.0, std::nullopt, 1.0);
  EXPECT_DOUBLE_EQ(fade.at(329).level, 0.5);
  EXPECT_EQ(fade.at(359).level, 0.0);
  EXPECT_FALSE(fade.active(359));  // at rest on the picture: the frame's own fade shows
}

TEST(FadeControl, AFadeStartedMidwayStartsFromWhereTheLevelIs) {
  FadeControl fade(10.0);
  fade.start(0, 1.0, glm::dvec3(0.0), 1.0);  // 10 frames
  const double halfway = fade.at(4).level;
  EXPECT_DOUBLE_EQ(halfway, 0.5);
  // Reversed at frame 5: from the level frame 5 had (u = 0.6), no jump.
  const double from = fade_curve(0.6);
  fade.start(5, 0.0, std::nullopt, 1.0);
  EXPECT_NEAR(fade.at(5).level, from * (1.0 - fade_curve(0.1)), 1e-15);
  EXPECT_NEAR(fade.at(9).level, from * 0.5, 1e-15);
  EXPECT_EQ(fade.at(14).level, 0.0);
}

TEST(FadeControl, ColoursJumpFromThePictureAndMoveWhileFaded) {
  FadeControl fade(10.0);
  const glm::dvec3 red(1.0, 0.0, 0.0), blue(0.0, 0.0, 1.0);
  fade.start(0, 1.0, red, 1.0);
  EXPECT_EQ(fade.at(0).colour, red);  // from the picture: red at once, the level ramps
  EXPECT_EQ(fade.at(9).colour, red);
  fade.start(20, 1.0, blue, 1.0);  // fully red: toward blue through the mix
  const scene::FadeState mid = fade.at(24);
  EXPECT_DOUBLE_EQ(mid.level, 1.0);
  EXPECT_DOUBLE_EQ(mid.colour.x, 0.5);
  EXPECT_DOUBLE_EQ(mid.colour.z, 0.5);
  EXPECT_EQ(fade.at(29).colour, blue);
}

TEST(FadeControl, ABlackoutIsAtItsTargetAtItsFirstFrame) {
  FadeControl fade(60.0);
  fade.start(7, 1.0, glm::dvec3(0.0), 0.0);
  EXPECT_EQ(fade.frames(), 0u);
  EXPECT_EQ(fade.at(6).level, 0.0);
  EXPECT_EQ(fade.at(7), (scene::FadeState{1.0, glm::dvec3(0.0)}));
  EXPECT_EQ(fade.frames_left(7), 0u);
  // A duration below half a frame is also at once.
  fade.start(10, 0.0, std::nullopt, 0.004);
  EXPECT_EQ(fade.at(10).level, 0.0);
}

TEST(FadeControl, AppliesOnlyWhileItDecidesTheFrame) {
  FadeControl fade(30.0);
  scene::FadeState recorded{0.25, glm::dvec3(0.0, 1.0, 0.0)};  // a recording's own fade
  fade.apply(recorded, 3);
  EXPECT_EQ(recorded.level, 0.25);  // the operator never faded: the recording's stays
  fade.start(3, 1.0, std::nullopt, 0.0);
  fade.apply(recorded, 3);
  EXPECT_EQ(recorded, (scene::FadeState{1.0, glm::dvec3(0.0)}));
}

TEST(FadeControl, RefusesValuesOutOfRangeNamingTheRange) {
  FadeControl fade(60.0);
  const auto expect_refused = [&](double level, glm::dvec3 colour, double seconds, const std::string& text) {
    try {
      fade.start(0, level, colour, seconds);
      FAIL() << "accepted " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  expect_refused(1.5, glm::dvec3(0.0), 1.0, "must be in [0, 1]");
  expect_refused(1.0, glm::dvec3(0.0), -1.0, "must be in [0, 3600] s");
  expect_refused(1.0, glm::dvec3(0.0, 2.0, 0.0), 1.0, "colour component 1 = 2: must be in [0, 1]");
  EXPECT_EQ(fade.at(0).level, 0.0);  // a refused fade changed nothing
  EXPECT_THROW(FadeControl(0.0), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::cluster
