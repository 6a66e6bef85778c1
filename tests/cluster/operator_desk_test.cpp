// The operator's desk without sockets (cluster/operator/operator_desk.h;
// docs/shows.md, "Playback"; docs/operator.md): what each command does to the
// next frame, the clock and the status, and what it refuses.
#include "cluster/operator/operator_desk.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "cluster/master/master_desk.h"
#include "scene/frame_scene.h"
#include "scene/scene_loader.h"
#include "show/show.h"

namespace zenith::cluster {
namespace {

namespace oc = operator_command;

const std::filesystem::path kSource = ZENITH_SOURCE_DIR;

std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

class OperatorDeskTest : public ::testing::Test {
 protected:
  OperatorDeskTest() : scene_(scene::load_scene(kSource / "configs/scenes/earth-sunset.json")) {
    TableSchedule::Actions actions;
    actions.prepare = [](TablePreparer::Job) {};
    actions.defer = [](std::function<void()>) {};
    schedule_.emplace(TableSchedule::Options{}, scene_, nullptr, sessions_, barrier_, actions);
    schedule_->prepare_initial([](const TablePreparer::Job& job) {
      return make_table_set(job.body, job.table_hash, std::make_shared<const std::vector<std::uint8_t>>(100, 1));
    });
  }

  /// The desk of the default show (`clock` nullptr) or of a show with `clock`.
  OperatorDesk desk(show::PlaybackClock* clock = nullptr) {
    door_.emplace(MasterDesk::Parts{config_, sessions_, barrier_, *schedule_, statistics_, progress_, nullptr, clock,
                                    30.0, [] { return std::nullopt; },
                                    [this](const std::string& reason) { stopped_ = reason; }});
    return OperatorDesk(*door_, OperatorDesk::Setup{config_, nullptr, clock, 30.0, false}, scene_);
  }

  FrameState frame(std::uint64_t n) const { return scene::default_show_frame(scene_, n, 0.0, {}, 0); }

  scene::Scene scene_;
  ClusterConfig config_;
  NodeSessions sessions_;
  FrameBarrier barrier_;
  NodeStatistics statistics_;
  FrameProgress progress_;
  std::optional<TableSchedule> schedule_;
  std::optional<MasterDesk> door_;  ///< the master's side of the desk's door, over the parts above
  std::string stopped_;
};

/// A show chasing the house's timecode: `play` resumes a stopped chase, `timecode offset` moves the
/// show's start, and the clock's own commands are refused with what to do instead.
TEST_F(OperatorDeskTest, AChasingShowTakesPlayAndAnOffsetAndRefusesTheClocksCommands) {
  const show::Show chasing = show::load_show(kSource / "tests/data/shows/chase-sunset.json");
  show::PlaybackClock clock(chasing.duration_s(), 10.0, false);
  show::ChaseSettings settings = chasing.timecode()->chase;
  settings.after_dropout = show::ChaseSettings::AfterDropout::stop;
  settings.freewheel_s = 0.0;
  show::TimecodeChase chase(settings);
  show::ChasePosition chased;  // the master's: the chase at its latest frame
  door_.emplace(MasterDesk::Parts{config_, sessions_, barrier_, *schedule_, statistics_, progress_, &chasing, &clock,
                                  10.0, [] { return std::nullopt; },
                                  [this](const std::string& reason) { stopped_ = reason; }, &chased});
  OperatorDesk d(*door_, OperatorDesk::Setup{config_, &chasing, &clock, 10.0, false, &chase}, scene_);

  // Locked on 01:00:05:00 onwards, then silent past the dropout: stopped.
  for (int f = 0; f < 5; ++f) chase.receive({{1, 0, 5, f}, show::TimecodeRate::fps25, f / 25.0});
  EXPECT_EQ(chase.position(0.2).state, show::ChaseState::locked);
  EXPECT_NEAR(chase.position(0.2).show_time_s, 5.2, 1e-9);
  EXPECT_EQ(chase.position(1.0).state, show::ChaseState::stopped);
  for (int f = 0; f < 3; ++f) chase.receive({{1, 0, 9, f}, show::TimecodeRate::fps25, 4.0 + f / 25.0});
  EXPECT_EQ(chase.position(4.1).state, show::ChaseState::stopped) << "the timecode is back: the show waits";
  EXPECT_EQ(d.on_line("play"), "chasing the house's timecode from 01:00:00:00 (25 fps)");
  chase.receive({{1, 0, 9, 3}, show::TimecodeRate::fps25, 4.12});
  EXPECT_EQ(chase.position(4.12).state, show::ChaseState::locked);
  EXPECT_NEAR(chase.position(4.12).show_time_s, 9.12, 1e-9);
  chased = chase.position(4.12);
  const nlohmann::json status = d.status()["timecode"];
  EXPECT_EQ(status["state"], "locked");
  EXPECT_EQ(status["last"], "01:00:09:03");
  EXPECT_EQ(status["rate"], "25");
  EXPECT_EQ(status["locates"], 0) << "the return after the dropout is no locate";
  EXPECT_EQ(status["before_start"], false);

  EXPECT_EQ(status["offset"], "01:00:00:00");

  EXPECT_EQ(d.on_line("timecode offset 01:00:02:00"), "show time 0 at 01:00:02:00 from the next frame on");
  EXPECT_NEAR(chase.position(4.12).show_time_s, 7.12, 1e-9);
  EXPECT_NE(d.on_line("timecode offset 01:00:02:30").find("frames [0, 25)"), std::string::npos);
  // The same from the web console, scripts and OSC desks: the JSON command.
  EXPECT_EQ(d.run(parse_operator_command({{"command", "timecode"}, {"offset", "01:00:03:00"}}), "console"),
            "show time 0 at 01:00:03:00 from the next frame on");
  chased = chase.position(4.12);
  EXPECT_NEAR(chased.show_time_s, 6.12, 1e-9);
  EXPECT_EQ(d.status()["timecode"]["offset"], "01:00:03:00");
  EXPECT_NE(refusal([&] { d.run(oc::TimecodeOffset{"01:00:03:29"}, "console"); }).find("frames [0, 25)"),
            std::string::npos)
      << "a label of 30 fps the show's 25 fps does not have";
  EXPECT_NE(d.on_line("seek 3").find("the show follows the house's timecode"), std::string::npos);
  EXPECT_NE(refusal([&] { d.run(oc::Pause{}, "control"); }).find("the show follows the house's timecode"),
            std::string::npos);
  EXPECT_EQ(clock.time_s(), 0.0) << "the clock was not touched";

  // A show on its own clock has no timecode to show or move.
  OperatorDesk own = desk(&clock);
  EXPECT_TRUE(own.status()["timecode"].is_null());
  EXPECT_NE(refusal([&] {
              own.run(oc::TimecodeOffset{"01:00:03:00"}, "console");
            }).find("the show runs on its own clock, not the house's timecode"),
            std::string::npos);
  EXPECT_NE(own.on_line("timecode offset 01:00:03:00").find("the show runs on its own clock"), std::string::npos);
}

TEST_F(OperatorDeskTest, TheExposureReplacesTheShowsFromTheNextFrameUntilCleared) {
  OperatorDesk d = desk();
  EXPECT_EQ(d.run(oc::Exposure{2.5}, "control"), "exposure 2.5 from the next frame on");
  FrameState next = frame(1);
  ASSERT_EQ(next.exposure, 25.0) << "the scene's exposure";
  d.shape(next);
  EXPECT_EQ(next.exposure, 2.5);
  EXPECT_EQ(d.status()["exposure_override"], 2.5);

  EXPECT_EQ(d.run(oc::Clear{oc::Clear::What::exposure, ""}, "control"),
            "the show's own exposure from the next frame on");
  FrameState after = frame(2);
  d.shape(after);
  EXPECT_EQ(after.exposure, 25.0);
  EXPECT_TRUE(d.status()["exposure_override"].is_null());
}

TEST_F(OperatorDeskTest, AFadeStartsAtTheNextFrameAndABlackoutIsBlackThere) {
  OperatorDesk d = desk();  // 30 Hz
  progress_.started = true;
  progress_.in_flight = frame(9);  // frame 9 is in flight: commands change frame 10 on
  EXPECT_EQ(d.run(oc::Fade{1.0, 1.0, std::array<double, 3>{0.0, 0.0, 0.0}}, "http 127.0.0.1"),
            "fade to level 1 of [0, 0, 0] over 30 frames (1 s at 30 Hz), frames 10 to 39");
  const auto level_at = [&](std::uint64_t n) {
    FrameState f = frame(n);
    d.shape(f);
    return f.fade.level;
  };
  EXPECT_EQ(level_at(9), 0.0);
  EXPECT_DOUBLE_EQ(level_at(24), 0.5);  // u = 15/30
  EXPECT_EQ(level_at(39), 1.0);
  progress_.in_flight = frame(50);
  EXPECT_EQ(d.status()["fade"]["operator"], true);
  EXPECT_EQ(d.run(oc::Blackout{false}, "osc 127.0.0.1"), "blackout off: the picture from frame 51 on");
  EXPECT_EQ(level_at(51), 0.0);
  EXPECT_EQ(d.run(oc::Blackout{true}, "osc 127.0.0.1"), "blackout from frame 51 on every node");
  FrameState black = frame(51);
  d.shape(black);
  EXPECT_EQ(black.fade, (scene::FadeState{1.0, glm::dvec3(0.0)}));
  EXPECT_EQ(d.status()["fade"]["frames_left"], 0);
}

TEST_F(OperatorDeskTest, TheSunIsSetInTheCamerasSkyAndAnAngleLeftOutKeepsItsValue) {
  OperatorDesk d = desk();
  EXPECT_EQ(d.run(oc::Sun{-6.0, std::nullopt}, "osc 10.0.0.5"),
            "sun at elevation -6°, azimuth 272° from the next frame on, until cleared");
  FrameState next = frame(1);
  d.shape(next);
  const SunOverride check(scene_);
  EXPECT_NEAR(check.angles_of(next).elevation_deg, -6.0, 1e-9);
  EXPECT_NEAR(check.angles_of(next).azimuth_deg, 272.0, 1e-9);
  EXPECT_EQ(d.run(oc::Clear{oc::Clear::What::sun, ""}, "control"), "the default show's sun from the next frame on");
  FrameState again = frame(1);
  d.shape(again);
  EXPECT_EQ(again, frame(1));
}

TEST_F(OperatorDeskTest, TheDefaultShowHasNoClock) {
  OperatorDesk d = desk();
  barrier_.start_at(7);
  EXPECT_EQ(d.on_line("status \r"), "default show at frame 7 (no show file: only status and quit)");
  EXPECT_EQ(d.on_line("pause"), "no show is playing: only 'status' and 'quit' are available");
  EXPECT_EQ(d.run(oc::Status{}, "control"), "default show at frame 7");
  EXPECT_EQ(refusal([&] { d.run(oc::Seek{2.0}, "control"); }),
            "seek 2.0: no show is playing (the default show has no clock: start the master with --show FILE for "
            "play, pause, seek, rate and loop)");
  EXPECT_EQ(d.on_line(""), "");
  EXPECT_TRUE(stopped_.empty());
  EXPECT_EQ(d.on_line("quit"), "stopping");
  EXPECT_EQ(stopped_, "stopped by the operator");
}

TEST_F(OperatorDeskTest, AShowsClockTakesPlaybackCommandsWithinItsDuration) {
  show::PlaybackClock clock(10.0, 30.0, false);
  OperatorDesk d = desk(&clock);
  EXPECT_EQ(d.on_line("pause"), "paused at 0.000 s of 10.000 s, rate 1, loop off");
  EXPECT_FALSE(clock.playing());
  EXPECT_EQ(d.on_line("rate 99").rfind("error: \"rate 99\": rate 99 is outside [-16, 16]; ", 0), 0u);
  EXPECT_EQ(refusal([&] { d.run(oc::Seek{12.0}, "http 127.0.0.1"); }),
            "command: /seconds = 12: must be in [0, 10] s (the show's duration)");
  d.run(oc::Seek{4.0}, "http 127.0.0.1");
  EXPECT_DOUBLE_EQ(clock.time_s(), 4.0);
  // A JSON line is a command as the HTTP console sends it; a bad one is refused with the reason.
  d.on_line(R"({"command": "play"})");
  EXPECT_TRUE(clock.playing());
  EXPECT_EQ(d.on_line(R"({"command": "seek", "seconds": -1})").rfind("error: ", 0), 0u);
  EXPECT_DOUBLE_EQ(clock.time_s(), 4.0) << "a refused command changes nothing";
}

TEST_F(OperatorDeskTest, ThePreviewNeedsTheHttpConsole) {
  OperatorDesk d = desk();
  EXPECT_EQ(refusal([&] { d.run(oc::Preview{true}, "control"); }),
            "preview: the dome preview is served at /api/preview: start the master with --operator-port");
  EXPECT_FALSE(d.wants_preview(0));
  EXPECT_EQ(d.preview_interval_frames(), 15u) << "two thumbnails a second at 30 fps";
}

TEST_F(OperatorDeskTest, AnAtmosphereChangeGoesToTheTableSchedule) {
  OperatorDesk d = desk();
  EXPECT_EQ(refusal([&] {
              d.run(oc::Set{"Earth", nlohmann::json::json_pointer("/aerosol/scattering/turbidity"), 100}, "control");
            }),
            "set Earth: /aerosol/scattering/turbidity = 100: must be in [1, 64]");
  EXPECT_TRUE(d.status()["live_atmospheres"].get<bool>());
}

}  // namespace
}  // namespace zenith::cluster
