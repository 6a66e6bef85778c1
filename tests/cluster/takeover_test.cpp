// A standby master becoming the master, without sockets
// (cluster/master/takeover.h; docs/cluster.md, "Standby master"): how the
// show continues (frame, show time, rate, pause, exposure, mismatches) and
// how the received versions join the master's table versions.
#include "cluster/master/takeover.h"

#include <gtest/gtest.h>

#include <memory>

#include "atmosphere/model_hash.h"
#include "scene/frame_scene.h"
#include "scene/scene_loader.h"
#include "test_support.h"

namespace zenith::cluster {
namespace {

const std::filesystem::path kSource = ZENITH_SOURCE_DIR;

/// The last frame `number` at `show_time_s`, the step before it `step_s`.
TakeoverState state_at(std::uint64_t number, double show_time_s, std::optional<double> step_s) {
  TakeoverState state;
  state.last_frame = FrameState{};
  state.last_frame->frame = number;
  state.last_frame->show_time_s = show_time_s;
  state.show_time_step_s = step_s;
  return state;
}

TEST(Takeover, TheShowGoesOnFromTheNextFrameAtTheLastStep) {
  const TakeoverState state = state_at(41, 4.1, 4.1 - 4.0);
  const Continuation c = continuation_of(state, *state.last_frame, 10.0);
  EXPECT_EQ(c.next_frame, 42u);
  EXPECT_DOUBLE_EQ(c.last_show_time_s, 4.1);
  EXPECT_EQ(c.rate, 1.0) << "4.1 - 4.0 is not 0.1 exactly, the rate is 1 exactly";
  EXPECT_FALSE(c.paused);
  EXPECT_FALSE(c.exposure.has_value());
  EXPECT_TRUE(c.mismatches.empty());

  EXPECT_NEAR(continuation_of(state_at(9, 3.0, 0.2), *state_at(9, 3.0, 0.2).last_frame, 10.0).rate, 2.0, 1e-9)
      << "played at twice the speed";
  EXPECT_TRUE(continuation_of(state_at(9, 3.0, 0.0), *state_at(9, 3.0, 0.0).last_frame, 10.0).paused);
  EXPECT_EQ(continuation_of(state_at(9, 3.0, std::nullopt), *state_at(9, 3.0, 0.0).last_frame, 10.0).rate, 1.0)
      << "one frame seen: the show's own rate";
  EXPECT_EQ(continuation_of(state_at(9, 0.0, -59.9), *state_at(9, 0.0, 0.0).last_frame, 10.0).rate, 1.0)
      << "a loop's wrap is no rate";
}

TEST(Takeover, AShowsClockGoesOnFromTheLastFrameAtItsRate) {
  show::PlaybackClock clock(10.0, 10.0, false);
  const TakeoverState state = state_at(41, 4.1, 0.2);
  continue_clock(continuation_of(state, *state.last_frame, 10.0), clock);
  EXPECT_NEAR(clock.next_frame_time_s(), 4.3, 1e-9) << "the frame after the last, at twice the speed";
  EXPECT_NEAR(clock.next_frame_time_s(), 4.5, 1e-9);

  show::PlaybackClock paused(10.0, 10.0, false);
  const TakeoverState held = state_at(41, 4.1, 0.0);
  continue_clock(continuation_of(held, *held.last_frame, 10.0), paused);
  EXPECT_DOUBLE_EQ(paused.next_frame_time_s(), 4.1) << "paused: the show time holds";
  EXPECT_FALSE(paused.playing());
}

TEST(Takeover, TheOperatorsExposureIsKeptAndAnotherShowIsReported) {
  TakeoverState state = state_at(5, 0.5, 0.1);
  state.last_frame->exposure = 3.0;
  FrameState expected = *state.last_frame;
  expected.exposure = 1.0;
  expected.sun_direction = {0, 1, 0};
  const Continuation c = continuation_of(state, expected, 10.0);
  EXPECT_EQ(c.exposure, std::optional<double>(3.0));
  EXPECT_EQ(c.mismatches, std::vector<std::string>{"sun direction"});
}

TEST(Takeover, TheReceivedVersionsBecomeTheMastersWithTheLastFramesCurrentOnes) {
  const scene::Scene scene = scene::load_scene(kSource / "configs/scenes/earth-sunset.json");
  const atmosphere::LoadedAtmosphere& earth = scene.bodies[0].atmosphere->loaded;
  const Digest hash = digest_from_hex(atmosphere::lookup_table_hash(earth.model));
  TakeoverState state = state_at(7, 0.7, 0.1);
  state.last_frame->atmospheres.push_back({scene.bodies[0].name, hash, 3});
  state.versions.push_back(
      {AtmosphereDefinition{scene.bodies[0].name, hash, earth.parameters.dump()},
       make_table_set(scene.bodies[0].name, hash, std::make_shared<const std::vector<std::uint8_t>>(100, 7))});
  TableVersions tables;
  adopt_takeover_tables(state, scene, tables, true);
  ASSERT_EQ(tables.current().size(), 1u);
  EXPECT_EQ(tables.current()[0].table_hash, hash);
  EXPECT_EQ(tables.current()[0].effective_from_frame, 3u) << "as the active master sent it";
  EXPECT_TRUE(tables.has_set(hash));
  EXPECT_NE(tables.definition(hash), nullptr) << "nodes that rejoin are sent the definition";
  EXPECT_EQ(tables.wanted_sets(), std::vector<Digest>{hash});

  TakeoverState wrong = state;
  wrong.versions[0].definition.table_hash = test::digest(9);  // parameters that hash to another set here
  TableVersions other;
  EXPECT_THROW(adopt_takeover_tables(wrong, scene, other, true), std::runtime_error);
  TakeoverState missing = state;
  missing.versions.clear();
  TableVersions none;
  EXPECT_THROW(adopt_takeover_tables(missing, scene, none, true), std::runtime_error);

  // The default show gives, for the same frame number, the state the active master sent.
  const FrameState expected = scene::default_show_frame(scene, 7, 0.1, tables.current(), 0);
  FrameState last = expected;
  last.frame = 7;
  TakeoverState same = state;
  same.last_frame = last;
  EXPECT_TRUE(continuation_of(same, expected, 10.0).mismatches.empty());
}

}  // namespace
}  // namespace zenith::cluster
