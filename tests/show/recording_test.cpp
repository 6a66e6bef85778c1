// Recordings: record → write → load gives back every frame state bit for bit.
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>

#include <gtest/gtest.h>

#include "show/show.h"
#include "show_test_support.h"

namespace zenith::show {
namespace {

using nlohmann::json;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(JsonDoubles, RoundTripBitForBit) {
  // nlohmann::json prints the shortest text that reads back as the same double.
  const double awkward[] = {0.1,
                            1.0 / 3.0,
                            1e-300,
                            std::numeric_limits<double>::denorm_min(),
                            std::numeric_limits<double>::min() / 3.0,
                            -0.0,
                            6371000.000000001,
                            std::numeric_limits<double>::max(),
                            2.0 / 3.0 * 1e22,
                            -123456.789e-200,
                            0.30000000000000004};
  for (double x : awkward) {
    const double back = json::parse(json(x).dump()).get<double>();
    EXPECT_TRUE(same_bits(x, back)) << json(x).dump();
  }
  EXPECT_EQ(json(-0.0).dump(), "-0.0");
  EXPECT_EQ(json(0.1).dump(), "0.1");
}

/// A keyframed show with an atmosphere track: the "live session" we record.
Show live_show(const std::filesystem::path& dir) {
  json show = test::minimal_show("earth-sunset");
  show["atmospheres"] = json::array(
      {{{"body", "Earth"},
        {"tracks",
         json::array({{{"parameter", "/aerosol/scattering/turbidity"},
                       {"step", 0.5},
                       {"keys", json::array({{{"t_s", 0}, {"value", 3.0}}, {{"t_s", 2}, {"value", 2.0}}})}}})}}});
  return load_show(test::write_file(dir / "live.json", show.dump()));
}

TEST(ShowRecorder, RecordedFramesReadBackExactly) {
  const auto dir = test::temp_folder("recorder");
  const Show live = live_show(dir);
  const auto path = dir / "session.json";
  std::vector<scene::FrameDescription> recorded;
  {
    ShowRecorder recorder(path, live.scene_path(), "session", 30.0);
    for (const AtmosphereVersion& v : live.atmosphere_versions(30.0)) recorder.add_version(v);
    for (std::uint64_t i = 0; i < 61; ++i) {
      scene::FrameDescription s = live.state_at(live.frame_time_s(i, 30.0), 1000 + i, scene::kRenderSunDisc);
      s.show_time_s = i / 30.0;
      // Awkward doubles, still a valid state.
      s.camera_position_m.x += i == 3 ? 1.0 / 3.0 : 0.1;
      s.sun_angular_radius_rad = i == 5 ? std::numeric_limits<double>::denorm_min() : s.sun_angular_radius_rad;
      s.sun_irradiance_W_m2_nm[2] = i == 7 ? 1e-300 : (i == 8 ? -0.0 : s.sun_irradiance_W_m2_nm[2]);
      s.atmospheres[0].effective_from_frame = 1000 + i / 2;
      // An operator's fade to a colour and back: recorded like any other state (none at the ends).
      if (i >= 20 && i < 40) s.fade = {std::sin(3.14159 * (i - 20) / 20.0), glm::dvec3(1.0, 1.0 / 3.0, 0.0)};
      recorder.record(s);
      recorded.push_back(s);
    }
    EXPECT_EQ(recorder.frames(), 61u);
    EXPECT_EQ(recorder.finish(), path);
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "session.json.partial"));

  const Show replay = load_show(path);
  EXPECT_EQ(replay.kind(), Show::Kind::recording);
  EXPECT_EQ(replay.frame_rate_hz(), 30.0);
  EXPECT_EQ(replay.frame_count(1.0), 61u);
  EXPECT_EQ(replay.duration_s(), 2.0);
  EXPECT_EQ(replay.scene_path(), live.scene_path());
  for (std::uint64_t i = 0; i < 61; ++i) {
    scene::FrameDescription expected = recorded[i];
    const std::uint64_t frame = 1000 + i;
    EXPECT_EQ(replay.state_at(replay.frame_time_s(i, 0.0), frame, 0), expected) << i;
  }
  EXPECT_TRUE(same_bits(replay.state_at(replay.frame_time_s(8, 0.0), 0, 0).sun_irradiance_W_m2_nm[2], -0.0));
  // Effective frames are clamped to the frame asked for; times between frames hold the earlier one.
  const scene::FrameDescription early = replay.state_at(replay.frame_time_s(10, 0.0) + 0.01, 3, 0);
  EXPECT_EQ(early.atmospheres[0].effective_from_frame, 3u);
  EXPECT_EQ(early.camera_position_m, recorded[10].camera_position_m);
  EXPECT_EQ(replay.atmosphere_versions(0.0).size(), 3u);
  for (const AtmosphereVersion& v : live.atmosphere_versions(30.0))
    ASSERT_NE(replay.find_version(v.table_hash), nullptr);
}

TEST(ShowRecorder, RefusesUnknownVersionsAndInvalidStates) {
  const auto dir = test::temp_folder("recorder_refuses");
  const Show live = live_show(dir);
  ShowRecorder recorder(dir / "r.json", live.scene_path(), "r", 30.0);
  scene::FrameDescription s = live.state_at(0.0, 0, 0);
  EXPECT_THROW(recorder.record(s), std::invalid_argument);  // version not added
  for (const AtmosphereVersion& v : live.atmosphere_versions(30.0)) recorder.add_version(v);
  recorder.record(s);
  recorder.record(s);  // the same show time again: a paused show is recorded as it was presented
  s.show_time_s = 1.0;
  s.exposure = std::nan("");
  EXPECT_THROW(recorder.record(s), std::invalid_argument);
  EXPECT_EQ(recorder.frames(), 2u);
}

/// A recording file, written and then spoiled.
std::filesystem::path spoiled_recording(const std::string& test, const std::function<void(json&)>& spoil) {
  const auto dir = test::temp_folder(test);
  const Show live = live_show(dir);
  const auto path = dir / "rec.json";
  {
    ShowRecorder recorder(path, live.scene_path(), "rec", 10.0);
    for (const AtmosphereVersion& v : live.atmosphere_versions(10.0)) recorder.add_version(v);
    for (std::uint64_t i = 0; i < 5; ++i) recorder.record(live.state_at(i * 0.5, i, 0));
  }
  std::ifstream in(path);
  json j = json::parse(in);
  spoil(j);
  return test::write_file(path, j.dump());
}

void expect_error(const std::filesystem::path& path, const std::string& key, const std::string& reason) {
  try {
    load_show(path);
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
  }
}

TEST(RecordingErrors, HashMismatch) {
  expect_error(
      spoiled_recording(
          "rec_hash",
          [](json& j) { j["recording"]["versions"][0]["parameters"]["aerosol"]["scattering"]["turbidity"] = 5.0; }),
      "/recording/versions/0/table_hash", "does not match the parameters");
}

TEST(RecordingErrors, UnlistedHash) {
  expect_error(spoiled_recording(
                   "rec_unlisted",
                   [](json& j) { j["recording"]["frames"][2]["atmospheres"][0]["table_hash"] = std::string(64, 'a'); }),
               "/recording/frames/2/atmospheres/0/table_hash", "not among the recording's /recording/versions");
}

TEST(Recording, ShowTimesThatPauseOrJumpBackPlayFrameByFrame) {
  // An operator paused (frames 1 and 2 at one show time) and sought back (frame 3):
  // the recording's own timeline is frame i at i / fps, whatever the show time.
  const Show replay = load_show(spoiled_recording("rec_time", [](json& j) {
    auto& frames = j["recording"]["frames"];
    frames[2]["show_time_s"] = frames[1]["show_time_s"];
    frames[3]["show_time_s"] = 0.0;
  }));
  const double fps = replay.frame_rate_hz();
  ASSERT_GE(replay.frame_count(fps), 4u);
  EXPECT_DOUBLE_EQ(replay.duration_s(), static_cast<double>(replay.frame_count(fps) - 1) / fps);
  const auto at = [&](std::uint64_t i) { return replay.state_at(replay.frame_time_s(i, fps), i, 0).show_time_s; };
  EXPECT_EQ(at(1), at(2));
  EXPECT_EQ(at(3), 0.0);
  EXPECT_GT(at(4), at(2));
}

TEST(RecordingErrors, WrongIrradianceCount) {
  expect_error(spoiled_recording("rec_irradiance",
                                 [](json& j) {
                                   j["recording"]["frames"][1]["sun_irradiance_W_m2_nm"] = {1.0, 2.0};
                                 }),
               "/recording/frames/1/sun_irradiance_W_m2_nm", "one per scene wavelength");
}

TEST(RecordingErrors, NotUnitQuaternion) {
  expect_error(spoiled_recording("rec_quat",
                                 [](json& j) {
                                   j["recording"]["frames"][0]["camera_orientation"] = {1.0, 0.1, 0, 0};
                                 }),
               "/recording/frames/0/camera_orientation", "unit quaternion");
}

TEST(RecordingErrors, UnknownRenderFlags) {
  expect_error(spoiled_recording("rec_flags", [](json& j) { j["recording"]["frames"][0]["render_flags"] = 64; }),
               "/recording/frames/0/render_flags", "must be an integer in [0, 31]");
}

TEST(RecordingErrors, FadeOutOfRange) {
  expect_error(spoiled_recording("rec_fade_level",
                                 [](json& j) {
                                   j["recording"]["frames"][2]["fade"] = {{"level", 1.5}, {"colour", {0, 0, 0}}};
                                 }),
               "/recording/frames/2/fade/level", "must be in [0, 1]");
  expect_error(spoiled_recording("rec_fade_colour",
                                 [](json& j) {
                                   j["recording"]["frames"][2]["fade"] = {{"level", 1}, {"colour", {0, 2, 0}}};
                                 }),
               "/recording/frames/2/fade/colour", "each component must be in [0, 1]");
}

TEST(RecordingErrors, UnknownFrameKey) {
  expect_error(spoiled_recording("rec_key", [](json& j) { j["recording"]["frames"][4]["time"] = 1; }),
               "/recording/frames/4/time", "unknown key");
}

}  // namespace
}  // namespace zenith::show
