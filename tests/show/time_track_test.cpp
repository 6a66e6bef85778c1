// A show's time track moves the scene's sky clock (docs/shows.md, "Time track").
#include <gtest/gtest.h>

#include <cmath>

#include "astro/sky_positions.h"
#include "core/units.h"
#include "scene/local_horizon.h"
#include "show/show.h"
#include "tests/scene/site_scene.h"
#include "tests/show/show_test_support.h"

namespace zenith::show {
namespace {

using nlohmann::json;

/// A dusk scene at Greenwich on the winter solstice, 2026, the sun placed by the ephemeris.
std::filesystem::path dusk_scene(const std::filesystem::path& dir) {
  const nlohmann::json scene = scene::testing::site_scene({.scene_name = "dusk",
                                                           .time = "2026-12-21T15:30:00Z",
                                                           .latitude_deg = 51.4769,
                                                           .longitude_deg = -0.0005,
                                                           .altitude_m = 46.0,
                                                           .look_azimuth_deg = 225.0,
                                                           .look_elevation_deg = 5.0});
  return test::write_file(dir / "dusk.json", scene.dump());
}

Show load(const std::filesystem::path& dir, const json& show) {
  return load_show(test::write_file(dir / "show.json", show.dump()));
}

TEST(TimeTrack, AnEveningInAMinute) {
  const auto dir = test::temp_folder("time-track");
  json show = {{"zenith_show", 1},
               {"name", "evening"},
               {"scene", dusk_scene(dir).string()},
               {"time", {{"time_rate", 120.0}, {"end_s", 60.0}}}};
  const Show s = load(dir, show);
  EXPECT_DOUBLE_EQ(s.duration_s(), 60.0);
  // Show time 45 s is 90 sky minutes after 15:30: 17:00 UTC.
  const auto sky = s.sky_time_at(45.0);
  ASSERT_TRUE(sky);
  EXPECT_EQ(sky->calendar_utc().hour, 17);
  EXPECT_EQ(sky->calendar_utc().minute, 0);
  // The frame's sun is the ephemeris' at that time, in the camera's horizon.
  const astro::SunPlace sun = astro::SkyPositions(*sky, s.scene().sky_clock->site).sun();
  const auto state = s.state_at(45.0, 0, 0);
  const scene::SkyAngles a =
      scene::local_horizon_at(state.camera_position_m, s.scene().bodies[0]).angles_of(state.sun_direction);
  EXPECT_NEAR(a.elevation_deg, sun.horizontal.altitude_rad / core::kDeg, 1e-6);
  EXPECT_NEAR(a.azimuth_deg, sun.horizontal.azimuth_rad / core::kDeg, 1e-6);
  // Sunset at Greenwich on the solstice is 15:53 UTC: at 17:00 the sun is ~−8° (civil dusk over).
  EXPECT_LT(a.elevation_deg, -6.0);
  EXPECT_GT(a.elevation_deg, -11.0);
  // The sun sinks through the evening.
  double last = 90.0;
  for (double t = 0.0; t <= 60.0; t += 5.0) {
    const auto f = s.state_at(t, 0, 0);
    const double e =
        scene::local_horizon_at(f.camera_position_m, s.scene().bodies[0]).angles_of(f.sun_direction).elevation_deg;
    EXPECT_LT(e, last);
    last = e;
  }
}

TEST(TimeTrack, ErrorsNameTheKey) {
  const auto dir = test::temp_folder("time-track-errors");
  auto message = [&](const json& show) {
    try {
      load(dir, show);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string scene = dusk_scene(dir).string();
  json show = {{"zenith_show", 1}, {"name", "x"}, {"scene", scene}, {"time", {{"time_rate", 1e6}}}};
  EXPECT_NE(message(show).find("/time/time_rate"), std::string::npos) << message(show);
  show["time"] = {{"start", "tomorrow"}};
  EXPECT_NE(message(show).find("/time/start"), std::string::npos) << message(show);
  show["time"] = {{"rate", 2}};
  EXPECT_NE(message(show).find("rate"), std::string::npos) << message(show);
  show["time"] = {{"time_rate", 60}};
  show["sun"] = json::array({{{"t_s", 0}, {"sky", {{"elevation_deg", 5}, {"azimuth_deg", 200}}}}});
  EXPECT_NE(message(show).find("both move the sun"), std::string::npos) << message(show);
  const json no_clock = {{"zenith_show", 1},
                         {"name", "x"},
                         {"scene", test::scene_file("earth-sunset").string()},
                         {"time", {{"time_rate", 60}}}};
  EXPECT_NE(message(no_clock).find("gives no \"time\" and \"site\""), std::string::npos) << message(no_clock);
}

}  // namespace
}  // namespace zenith::show
