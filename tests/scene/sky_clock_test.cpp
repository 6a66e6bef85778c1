// A scene's "time" and "site" place the sun by the ephemeris (scene/sky_clock.h,
// docs/scenes.md "Time and place").
#include <gtest/gtest.h>

#include <cmath>

#include "core/json_reader.h"
#include "core/units.h"
#include "scene/local_horizon.h"
#include "scene/scene_loader.h"
#include "tests/scene/site_scene.h"

namespace zenith::scene {
namespace {

using nlohmann::json;

/// NREL SPA's example (Reda & Andreas 2004): Golden, Colorado, 2003-10-17 19:30:30 UTC;
/// the camera stands at the site itself.
json golden_scene() {
  return testing::site_scene({.scene_name = "golden",
                              .time = "2003-10-17T19:30:30Z",
                              .latitude_deg = 39.742476,
                              .longitude_deg = -105.1786,
                              .altitude_m = 1830.14,
                              .look_azimuth_deg = 180.0,
                              .look_elevation_deg = 30.0});
}

Scene parse(const json& j) { return parse_scene(j, "sky-clock.json", ::testing::TempDir()); }

std::string error_of(const json& j) {
  try {
    parse(j);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SkyClock, TimeAndSitePlaceTheSun) {
  const Scene scene = parse(golden_scene());
  ASSERT_TRUE(scene.sky_clock);
  EXPECT_EQ(scene.sky_clock->time.hour, 19);
  EXPECT_DOUBLE_EQ(scene.sky_clock->site.altitude_m, 1830.14);
  const SkyAngles a = local_horizon_at(scene.camera.position_m, scene.bodies[0]).angles_of(scene.sun.direction);
  // The report's geometric elevation 39.8721° (its 50.11162° zenith angle less its
  // refraction) and azimuth 194.34024°: astro/'s test holds them to 3″; here the
  // scene frame must not lose them.
  EXPECT_NEAR(a.elevation_deg, 39.8721, 2e-3);
  EXPECT_NEAR(a.azimuth_deg, 194.34024, 2e-3);
  EXPECT_NEAR(scene.sun.angular_radius_rad / core::kDeg * 60.0, 16.1, 0.1);  // from the ephemeris' distance
}

TEST(SkyClock, BadInputNamesTheKey) {
  json j = golden_scene();
  j.erase("site");
  EXPECT_NE(error_of(j).find("/site: missing"), std::string::npos) << error_of(j);
  j = golden_scene();
  j["time"] = "2003-10-17T19:30:30+02:00";
  EXPECT_NE(error_of(j).find("/time"), std::string::npos);
  EXPECT_NE(error_of(j).find("only UTC"), std::string::npos) << error_of(j);
  j = golden_scene();
  j["time"] = "2003-02-30T19:30:30Z";
  EXPECT_NE(error_of(j).find("/time"), std::string::npos) << error_of(j);
  j = golden_scene();
  j["site"]["latitude_deg"] = 95;
  EXPECT_NE(error_of(j).find("/site/latitude_deg = 95"), std::string::npos) << error_of(j);
  j = golden_scene();
  j["site"]["elevation"] = 3;
  EXPECT_NE(error_of(j).find("elevation"), std::string::npos) << error_of(j);
  j = golden_scene();
  j["sun"] = json::parse(R"({"sky": {"elevation_deg": 10, "azimuth_deg": 90}})");
  EXPECT_NE(error_of(j).find("/sun/sky: is not used"), std::string::npos) << error_of(j);
  j = golden_scene();
  j["bodies"][0]["name"] = "Mars";
  j["bodies"][0]["atmosphere"] = "mars";
  j["camera"]["surface"]["body"] = "Mars";
  EXPECT_NE(error_of(j).find("the camera's body is \"Mars\""), std::string::npos) << error_of(j);
  // Without "time" and "site" a sun must still be given.
  j = golden_scene();
  j.erase("time");
  j.erase("site");
  EXPECT_NE(error_of(j).find("give exactly one of"), std::string::npos) << error_of(j);
}

TEST(NightSky, FloorAndLightPollutionInPhysicalUnits) {
  json j = golden_scene();
  j["night_sky"] = {{"zenith_v_mag_arcsec2", 21.8}};
  j["light_pollution"] = {{"zenith_mcd_m2", 2.5}, {"colour_temperature_K", 4000}};
  const Scene scene = parse(j);
  ASSERT_TRUE(scene.night_sky);
  EXPECT_DOUBLE_EQ(scene.night_sky->floor.zenith_v_mag_arcsec2, 21.8);
  EXPECT_DOUBLE_EQ(scene.night_sky->light_pollution.zenith_mcd_m2, 2.5);
  EXPECT_DOUBLE_EQ(scene.night_sky->light_pollution.colour_temperature_K, 4000.0);
  // A Bortle class becomes mcd/m²: class 1 is the natural sky, class 5 (20.0 mag/arcsec²) ~1 mcd/m².
  j.erase("night_sky");
  j["light_pollution"] = {{"bortle", 1}};
  EXPECT_LT(parse(j).night_sky->light_pollution.zenith_mcd_m2, 0.05);
  j["light_pollution"] = {{"bortle", 5}};
  const double b5 = parse(j).night_sky->light_pollution.zenith_mcd_m2;
  EXPECT_GT(b5, 0.5);
  EXPECT_LT(b5, 3.0);
  // Errors name the key and the range.
  j["light_pollution"] = {{"bortle", 10}};
  EXPECT_NE(error_of(j).find("/light_pollution/bortle"), std::string::npos) << error_of(j);
  j["light_pollution"] = {{"bortle", 3}, {"zenith_mcd_m2", 1.0}};
  EXPECT_NE(error_of(j).find("give exactly one of"), std::string::npos) << error_of(j);
  j["light_pollution"] = {{"zenith_mcd_m2", -1.0}};
  EXPECT_NE(error_of(j).find("/light_pollution/zenith_mcd_m2 = -1"), std::string::npos) << error_of(j);
  j.erase("light_pollution");
  j["night_sky"] = {{"zenith_v_mag_arcsec2", 25}};
  EXPECT_NE(error_of(j).find("/night_sky/zenith_v_mag_arcsec2 = 25"), std::string::npos) << error_of(j);
}

TEST(NightSky, ScintillationIsOffUnlessAskedAndItsParametersAreChecked) {
  json j = golden_scene();
  j["night_sky"] = {{"zenith_v_mag_arcsec2", 21.8}};
  EXPECT_FALSE(parse(j).night_sky->scintillation);
  j["night_sky"]["scintillation"] = false;
  EXPECT_FALSE(parse(j).night_sky->scintillation);
  j["night_sky"]["scintillation"] = true;  // the defaults: Osborn et al.'s median C_Y, a dark-adapted eye
  const auto defaults = parse(j).night_sky->scintillation;
  ASSERT_TRUE(defaults);
  EXPECT_DOUBLE_EQ(defaults->c_y, 1.5);
  EXPECT_DOUBLE_EQ(defaults->pupil_mm, 7.0);
  EXPECT_DOUBLE_EQ(defaults->integration_s, 0.1);
  j["night_sky"]["scintillation"] = {{"c_y", 1.2}, {"integration_s", 0.05}};
  const auto given = parse(j).night_sky->scintillation;
  ASSERT_TRUE(given);
  EXPECT_DOUBLE_EQ(given->c_y, 1.2);
  EXPECT_DOUBLE_EQ(given->integration_s, 0.05);
  EXPECT_DOUBLE_EQ(given->turbulence_height_m, 10000.0);
  // Errors name the key and the range.
  j["night_sky"]["scintillation"] = {{"c_y", 9}};
  EXPECT_NE(error_of(j).find("/night_sky/scintillation/c_y = 9"), std::string::npos) << error_of(j);
  j["night_sky"]["scintillation"] = {{"seeing", 1}};
  EXPECT_NE(error_of(j).find("seeing"), std::string::npos) << error_of(j);
  j["night_sky"]["scintillation"] = "yes";
  EXPECT_NE(error_of(j).find("/night_sky/scintillation"), std::string::npos) << error_of(j);
  EXPECT_NE(error_of(j).find("must be true, false or an object"), std::string::npos) << error_of(j);
}

}  // namespace
}  // namespace zenith::scene
