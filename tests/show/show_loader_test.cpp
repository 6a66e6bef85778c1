// Keyframed shows: loading, evaluation, atmosphere versions, table plans.
#include <cmath>
#include <thread>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "atmosphere/model_hash.h"
#include "core/sha256.h"
#include "core/units.h"
#include "scene/scene_loader.h"
#include "show/show.h"
#include "show/table_plan.h"
#include "show_test_support.h"

namespace zenith::show {
namespace {

using nlohmann::json;
using test::minimal_show;
using test::temp_folder;
using test::write_file;

Show load(const std::string& test, const json& show) {
  return load_show(write_file(temp_folder(test) / "show.json", show.dump(2)));
}

double altitude_m(const Show& show, const glm::dvec3& p) {
  const scene::Body& earth = show.scene().bodies[0];
  return glm::length(p - earth.position_m) - earth.radius_m;
}

json surface_key(double t, double lat, double lon, double altitude) {
  return {{"t_s", t},
          {"surface", {{"body", "Earth"}, {"latitude_deg", lat}, {"longitude_deg", lon}, {"altitude_m", altitude}}},
          {"look", {{"azimuth_deg", 90}, {"elevation_deg", -10}}}};
}

TEST(ShowLoader, WithoutTracksEveryFrameIsTheScene) {
  const Show show = load("no_tracks", minimal_show("earth-sunset"));
  EXPECT_EQ(show.kind(), Show::Kind::keyframed);
  EXPECT_EQ(show.duration_s(), 0.0);
  EXPECT_EQ(show.frame_rate_hz(), 30.0);
  EXPECT_EQ(show.frame_count(30.0), 1u);
  const scene::FrameDescription s = show.state_at(5.0, 7, scene::kRenderSunDisc);
  EXPECT_EQ(s.frame, 7u);
  EXPECT_EQ(s.show_time_s, 0.0);
  EXPECT_EQ(s.camera_position_m, show.scene().camera.position_m);
  EXPECT_EQ(s.camera_orientation, show.scene().camera.orientation);
  EXPECT_EQ(s.exposure, 25.0);
  EXPECT_EQ(s.sun_direction, show.scene().sun.direction);
  EXPECT_EQ(s.sun_irradiance_W_m2_nm, show.scene().sun.irradiance_W_m2_nm);
  EXPECT_EQ(s.render_flags, scene::kRenderSunDisc);
  ASSERT_EQ(s.atmospheres.size(), 1u);
  EXPECT_EQ(s.atmospheres[0].body_name, "Earth");
  EXPECT_EQ(core::to_hex(s.atmospheres[0].table_hash),
            atmosphere::lookup_table_hash(show.scene().bodies[0].atmosphere->loaded.model));
}

/// The "timecode" block: the rate, the label at show time 0 as the chase's offset, what a dropout does.
TEST(ShowLoader, TheHouseTimecodeItChases) {
  EXPECT_FALSE(load("timecode_none", minimal_show("earth-sunset")).timecode());
  const Show show = load(
      "timecode",
      minimal_show("earth-sunset",
                   {{"timecode",
                     {{"rate", "29.97df"}, {"start", "01:00:00;00"}, {"freewheel_s", 4}, {"after_dropout", "stop"}}}}));
  ASSERT_TRUE(show.timecode());
  EXPECT_EQ(show.timecode()->rate, TimecodeRate::fps29_97_drop);
  EXPECT_NEAR(show.timecode()->chase.offset_s, 107892.0 * 1001.0 / 30000.0, 1e-9);  // 3599.9964 s
  EXPECT_EQ(show.timecode()->chase.freewheel_s, 4.0);
  EXPECT_EQ(show.timecode()->chase.after_dropout, ChaseSettings::AfterDropout::stop);
  const Show defaults = load("timecode_defaults",
                             minimal_show("earth-sunset", {{"timecode", {{"rate", "25"}, {"start", "10:00:00:00"}}}}));
  EXPECT_EQ(defaults.timecode()->chase.offset_s, 36000.0);
  EXPECT_EQ(defaults.timecode()->chase.freewheel_s, ChaseSettings{}.freewheel_s);
  EXPECT_EQ(defaults.timecode()->chase.after_dropout, ChaseSettings::AfterDropout::hold);
}

TEST(ShowLoader, FrameCountsAndTimes) {
  const Show show = load(
      "frames",
      minimal_show("earth-sunset",
                   {{"exposure", json::array({{{"t_s", 0}, {"exposure", 10}}, {{"t_s", 2.5}, {"exposure", 20}}})}}));
  EXPECT_EQ(show.duration_s(), 2.5);
  EXPECT_EQ(show.frame_count(30.0), 76u);  // floor(75 + 1e-9) + 1
  EXPECT_EQ(show.frame_count(4.0), 11u);
  EXPECT_EQ(show.frame_count(3.0), 8u);  // 7.5 → 7, + 1
  EXPECT_EQ(show.frame_time_s(75, 30.0), 2.5);
  EXPECT_THROW(show.frame_count(0.0), std::invalid_argument);
}

TEST(ShowLoader, ExposureIsMonotoneInLogExposure) {
  const Show show =
      load("exposure",
           minimal_show("earth-sunset",
                        {{"exposure", json::array({{{"t_s", 0}, {"exposure", 40}}, {{"t_s", 10}, {"exposure", 4}}})}}));
  EXPECT_EQ(show.state_at(0.0, 0, 0).exposure, 40.0);
  EXPECT_NEAR(show.state_at(5.0, 0, 0).exposure, std::sqrt(160.0), 1e-12);  // geometric mean halfway
  EXPECT_EQ(show.state_at(10.0, 0, 0).exposure, 4.0);
  EXPECT_NEAR(show.state_at(20.0, 0, 0).exposure, 4.0, 1e-12);  // clamped to the duration
}

TEST(ShowLoader, DescentFrom400kmTo2mStaysAboveGroundAndIsSmooth) {
  const json keys =
      json::array({surface_key(0, 10, 20, 400000), surface_key(30, 12, 24, 5000), surface_key(60, 12.5, 25, 2)});
  const Show show = load("descent", minimal_show("earth-ground-noon", {{"camera", keys}}));
  double previous_altitude = 1e300, previous_speed = -1.0;
  glm::dvec3 previous = show.state_at(0.0, 0, 0).camera_position_m;
  for (int i = 1; i <= 6000; ++i) {
    const double t = i * 0.01;
    const glm::dvec3 p = show.state_at(t, 0, 0).camera_position_m;
    const double h = altitude_m(show, p);
    ASSERT_GE(h, 2.0 - 1e-6) << t;
    ASSERT_LE(h, previous_altitude + 1e-6) << t;  // a descent never climbs
    previous_altitude = h;
    const double speed = glm::length(p - previous) / 0.01;
    if (previous_speed > 1.0) {
      ASSERT_LT(std::abs(speed - previous_speed) / previous_speed, 0.05) << t;  // no jumps in speed
    }
    previous_speed = speed;
    previous = p;
  }
  EXPECT_NEAR(altitude_m(show, show.state_at(60.0, 0, 0).camera_position_m), 2.0, 1e-6);
  EXPECT_NEAR(altitude_m(show, show.state_at(30.0, 0, 0).camera_position_m), 5000.0, 1e-6);
}

TEST(ShowLoader, CameraKeysAreHitExactlyAtTheirTimes) {
  const json keys =
      json::array({surface_key(0, 0, 0, 400000), surface_key(20, 0, 3, 400000), surface_key(40, 1, 6, 400000)});
  const Show show = load("camera_keys", minimal_show("earth-orbit-limb", {{"camera", keys}}));
  for (std::size_t i = 0; i < keys.size(); ++i) {
    json object = keys[i];
    object.erase("t_s");
    const scene::CameraPlacement key = scene::parse_camera(object, show.scene(), "key", "");
    const scene::FrameDescription s = show.state_at(keys[i]["t_s"].get<double>(), 0, 0);
    EXPECT_NEAR(glm::length(s.camera_position_m - key.camera.position_m), 0.0, 1e-6) << i;
    EXPECT_NEAR(std::abs(glm::dot(s.camera_orientation, key.camera.orientation)), 1.0, 1e-15) << i;
  }
  // An orbital pass at constant altitude stays at that altitude between keys.
  for (int i = 0; i <= 400; ++i)
    EXPECT_NEAR(altitude_m(show, show.state_at(i * 0.1, 0, 0).camera_position_m), 400000.0, 1e-6);
}

TEST(ShowLoader, FreeCameraPathMustClearTheGround) {
  // Two position keys on opposite sides of Earth: the straight path goes through it.
  const json keys = json::array({{{"t_s", 0}, {"position_m", {7e6, 0, 0}}, {"forward", {0, 1, 0}}},
                                 {{"t_s", 10}, {"position_m", {-7e6, 0, 0}}, {"forward", {0, 1, 0}}}});
  try {
    load("free_path", minimal_show("earth-orbit-limb", {{"camera", keys}}));
    FAIL() << "accepted a path through the Earth";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "/camera/1");
    EXPECT_NE(std::string(e.what()).find("Earth"), std::string::npos) << e.what();
  }
}

TEST(ShowLoader, SunKeysInTheSkyFollowTheGreatCircle) {
  const json sun = json::array({{{"t_s", 0}, {"sky", {{"elevation_deg", -8}, {"azimuth_deg", 90}}}},
                                {{"t_s", 20}, {"sky", {{"elevation_deg", 10}, {"azimuth_deg", 90}}}}});
  const Show show = load("sun", minimal_show("earth-ground-noon", {{"sun", sun}}));
  // The local zenith at the (fixed) camera.
  const glm::dvec3 up = glm::normalize(show.scene().camera.position_m);
  for (int i = 0; i <= 20; ++i) {
    const scene::FrameDescription s = show.state_at(i, 0, 0);
    const double elevation_deg = std::asin(glm::dot(s.sun_direction, up)) * 180.0 / zenith::core::kPi;
    EXPECT_NEAR(elevation_deg, -8.0 + 18.0 * i / 20.0, 1e-9) << i;  // a vertical great circle, constant speed
  }
}

json turbidity_show(double step) {
  return minimal_show(
      "earth-sunset",
      {{"atmospheres",
        json::array({{{"body", "Earth"},
                      {"tracks", json::array({{{"parameter", "/aerosol/scattering/turbidity"},
                                               {"step", step},
                                               {"keys", json::array({{{"t_s", 0}, {"value", 3.0}},
                                                                     {{"t_s", 10}, {"value", 2.0}}})}}})}}})}});
}

TEST(ShowLoader, AtmosphereHashChangesExactlyWhenTheQuantizedValueDoes) {
  const Show show = load("turbidity", turbidity_show(0.25));
  // Raw turbidity 3 − t/10; quantized to 0.25: 3 until t = 1.25, then 2.75, ...
  scene::TableHash previous = show.state_at(0.0, 0, 0).atmospheres[0].table_hash;
  double previous_level = 3.0;
  int changes = 0;
  for (int i = 1; i <= 1000; ++i) {
    const double t = i * 0.01;
    const scene::TableHash hash = show.state_at(t, 0, 0).atmospheres[0].table_hash;
    const double level = std::round((3.0 - t / 10.0) / 0.25) * 0.25;
    EXPECT_EQ(hash != previous, level != previous_level) << t;
    changes += hash != previous;
    const AtmosphereVersion* version = show.find_version(hash);
    ASSERT_NE(version, nullptr);
    EXPECT_EQ(version->parameters["aerosol"]["scattering"]["turbidity"].get<double>(), level) << t;
    EXPECT_EQ(core::to_hex(hash), atmosphere::lookup_table_hash(version->loaded.model));
    previous = hash;
    previous_level = level;
  }
  EXPECT_EQ(changes, 4);
  const std::vector<AtmosphereVersion> versions = show.atmosphere_versions(30.0);
  ASSERT_EQ(versions.size(), 5u);
  EXPECT_EQ(versions.front().parameters["aerosol"]["scattering"]["turbidity"], 3.0);
  EXPECT_EQ(versions.back().parameters["aerosol"]["scattering"]["turbidity"], 2.0);
  // The scene's own set (turbidity 2.0) is the last one.
  EXPECT_EQ(core::to_hex(versions.back().table_hash),
            atmosphere::lookup_table_hash(show.scene().bodies[0].atmosphere->loaded.model));
  EXPECT_EQ(load("turbidity_coarse", turbidity_show(0.5)).atmosphere_versions(30.0).size(), 3u);
}

TEST(ShowLoader, StateAtIsSafeFromSeveralThreads) {
  const Show show = load("threads", turbidity_show(0.125));
  std::vector<std::vector<scene::TableHash>> seen(4);
  std::vector<std::thread> threads;
  for (int k = 0; k < 4; ++k)
    threads.emplace_back([&, k] {
      for (int i = 0; i <= 100; ++i) seen[k].push_back(show.state_at(i * 0.1, 0, 0).atmospheres[0].table_hash);
    });
  for (std::thread& t : threads) t.join();
  for (int k = 1; k < 4; ++k) EXPECT_EQ(seen[k], seen[0]);
  EXPECT_EQ(show.atmosphere_versions(10.0).size(), 9u);
}

TEST(ShowLoader, HeldTrackRemovesOzone) {
  const json show_json = minimal_show(
      "earth-sunset",
      {{"atmospheres",
        json::array(
            {{{"body", "Earth"},
              {"tracks",
               json::array({{{"parameter", "/ozone"},
                             {"keys", json::array({{{"t_s", 0}, {"value", nullptr}},
                                                   {{"t_s", 4},
                                                    {"value", json::object({{"profile", "us_standard_1976"},
                                                                            {"cross_sections", "bogumil2003"},
                                                                            {"temperature_K", 233}})}}})}}})}}})}});
  const Show show = load("ozone", show_json);
  const AtmosphereVersion* without = show.find_version(show.state_at(1.0, 0, 0).atmospheres[0].table_hash);
  const AtmosphereVersion* with = show.find_version(show.state_at(4.0, 0, 0).atmospheres[0].table_hash);
  ASSERT_TRUE(without && with);
  EXPECT_FALSE(without->parameters.contains("ozone"));
  EXPECT_TRUE(with->parameters.contains("ozone"));
  EXPECT_NE(without->table_hash, with->table_hash);
  // With ozone back as the scene has it, the tables are the scene's.
  EXPECT_EQ(core::to_hex(with->table_hash),
            atmosphere::lookup_table_hash(show.scene().bodies[0].atmosphere->loaded.model));
}

TEST(ApplyState, CopiesTheFrameAndSwapsAtmospheres) {
  const Show show = load("apply", turbidity_show(0.5));
  std::map<scene::TableHash, AtmosphereVersion> versions;
  for (const AtmosphereVersion& v : show.atmosphere_versions(30.0)) versions.emplace(v.table_hash, v);
  scene::Scene scene = show.scene();
  const scene::FrameDescription s = show.state_at(0.0, 0, 0);
  apply_state(s, versions, scene);
  EXPECT_EQ(scene.bodies[0].atmosphere->loaded.parameters["aerosol"]["scattering"]["turbidity"], 3.0);
  EXPECT_EQ(scene.camera.exposure, s.exposure);
  scene::FrameDescription unknown = s;
  unknown.atmospheres[0].table_hash[0] ^= 1;
  EXPECT_THROW(apply_state(unknown, versions, scene), std::invalid_argument);
  scene::FrameDescription other_body = s;
  other_body.atmospheres[0].body_name = "Mars";
  EXPECT_THROW(apply_state(other_body, versions, scene), std::invalid_argument);
  scene::FrameDescription wrong_owner = s;
  versions.begin()->second.body = "Mars";
  wrong_owner.atmospheres[0].table_hash = versions.begin()->first;
  EXPECT_THROW(apply_state(wrong_owner, versions, scene), std::invalid_argument);
}

TEST(TablePlan, CountsFramesPerSetAndChecksTheCache) {
  const Show show = load("plan", turbidity_show(0.5));
  const auto dir = temp_folder("plan_cache");
  atmosphere::lut::TableCache cache(dir);
  atmosphere::lut::PrecomputeOptions options;
  options.sizes = atmosphere::lut::TableSizes::small();
  const TablePlan plan = plan_tables(show, 10.0, options, cache);
  EXPECT_EQ(plan.frame_count, 101u);
  ASSERT_EQ(plan.sets.size(), 3u);
  // Raw turbidity 3 − t/10 in steps of 0.5: halves round away from zero, so
  // 3 for t ≤ 2.5 (frames 0..25), 2.5 for t in (2.5, 7.5] (26..75), 2 after.
  EXPECT_EQ(plan.sets[0].first_frame, 0u);
  EXPECT_EQ(plan.sets[0].frames, 26u);
  EXPECT_EQ(plan.sets[1].first_frame, 26u);
  EXPECT_EQ(plan.sets[1].frames, 50u);
  EXPECT_EQ(plan.sets[2].first_frame, 76u);
  EXPECT_EQ(plan.sets[2].frames, 25u);
  const atmosphere::lut::TableSizes& s = options.sizes;
  const std::uint64_t texels =
      s.transmittance_mu * s.transmittance_r + s.irradiance_mu_s * s.irradiance_r + 3 * s.scattering_texels();
  EXPECT_EQ(plan.sets[0].bytes, texels * 3 * 4);
  EXPECT_EQ(plan.total_bytes(), 3 * texels * 3 * 4);
  EXPECT_EQ(plan.missing(), 3u);
  // A file where the cache expects the second set makes it cached.
  const auto path = cache.path_for(atmosphere::lut::table_set_key(plan.sets[1].version.loaded.model, options));
  std::filesystem::create_directories(path.parent_path());
  write_file(path, "tables");
  const TablePlan again = plan_tables(show, 10.0, options, cache);
  EXPECT_TRUE(again.sets[1].cached);
  EXPECT_FALSE(again.sets[0].cached);
  EXPECT_EQ(again.missing(), 2u);
  const std::string report = describe(again, 60.0);
  EXPECT_NE(report.find("3 lookup-table sets for 101 frames at 10 fps"), std::string::npos) << report;
  EXPECT_NE(report.find("/aerosol/scattering/turbidity = 2.5"), std::string::npos) << report;
  EXPECT_NE(report.find("2 to compute (about 120 s)"), std::string::npos) << report;
}

}  // namespace
}  // namespace zenith::show
