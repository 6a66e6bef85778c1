// Malformed show files: every error names the file, the JSON pointer and the reason.
#include <functional>

#include <gtest/gtest.h>

#include "show/show.h"
#include "show_test_support.h"

namespace zenith::show {
namespace {

using nlohmann::json;

/// A valid show using every kind of track, which each case breaks in one place.
json valid_show() {
  json show = test::minimal_show("earth-sunset");
  show["fps"] = 24;
  show["camera"] =
      json::array({{{"t_s", 0},
                    {"surface", {{"body", "Earth"}, {"latitude_deg", 45}, {"longitude_deg", 5}, {"altitude_m", 2}}},
                    {"look", {{"azimuth_deg", 270}, {"elevation_deg", 5}}}},
                   {{"t_s", 10},
                    {"surface", {{"body", "Earth"}, {"latitude_deg", 45}, {"longitude_deg", 5}, {"altitude_m", 50}}},
                    {"look", {{"azimuth_deg", 260}, {"elevation_deg", 8}}}}});
  show["sun"] = json::array({{{"t_s", 0}, {"sky", {{"elevation_deg", 4}, {"azimuth_deg", 272}}}},
                             {{"t_s", 10}, {"sky", {{"elevation_deg", 0}, {"azimuth_deg", 274}}}}});
  show["exposure"] = json::array({{{"t_s", 0}, {"exposure", 20}}, {{"t_s", 10}, {"exposure", 30}}});
  show["atmospheres"] = json::array(
      {{{"body", "Earth"},
        {"tracks",
         json::array({{{"parameter", "/aerosol/scattering/turbidity"},
                       {"step", 0.5},
                       {"keys", json::array({{{"t_s", 0}, {"value", 2.0}}, {{"t_s", 10}, {"value", 3.0}}})}}})}}});
  return show;
}

struct Case {
  const char* name;
  std::function<void(json&)> spoil;
  const char* key;     ///< the JSON pointer the error must name
  const char* reason;  ///< a part of the message
};

const Case kCases[] = {
    {"wrong_version", [](json& j) { j["zenith_show"] = 2; }, "/zenith_show", "unsupported show format version"},
    {"version_missing", [](json& j) { j.erase("zenith_show"); }, "/zenith_show", "missing required key"},
    {"unknown_top_key", [](json& j) { j["fsp"] = 30; }, "/fsp", "unknown key"},
    {"empty_name", [](json& j) { j["name"] = ""; }, "/name", "must not be empty"},
    {"name_not_string", [](json& j) { j["name"] = 3; }, "/name", "must be a string"},
    {"missing_scene", [](json& j) { j.erase("scene"); }, "/scene", "missing required key"},
    {"scene_not_found", [](json& j) { j["scene"] = "no-such-scene.json"; }, "/scene", "file not found"},
    {"cluster_not_found", [](json& j) { j["cluster"] = "no-such-cluster.json"; }, "/cluster", "file not found"},
    {"fps_zero", [](json& j) { j["fps"] = 0; }, "/fps", "(0, 240]"},
    {"fps_too_high", [](json& j) { j["fps"] = 500; }, "/fps", "must be in [0, 240] Hz"},
    {"loop_not_bool", [](json& j) { j["loop"] = "yes"; }, "/loop", "must be true or false"},
    {"timecode_rate",
     [](json& j) {
       j["timecode"] = {{"rate", "50"}, {"start", "01:00:00:00"}};
     },
     "/timecode/rate", "29.97df"},
    {"timecode_start",
     [](json& j) {
       j["timecode"] = {{"rate", "25"}, {"start", "01:00:00:25"}};
     },
     "/timecode/start", "frames [0, 25)"},
    {"timecode_drop_label",
     [](json& j) {
       j["timecode"] = {{"rate", "29.97df"}, {"start", "01:01:00;00"}};
     },
     "/timecode/start", "drop-frame skips frames 0 and 1"},
    {"timecode_after_dropout",
     [](json& j) {
       j["timecode"] = {{"rate", "25"}, {"start", "01:00:00:00"}, {"after_dropout", "pause"}};
     },
     "/timecode/after_dropout", "hold"},
    {"timecode_freewheel",
     [](json& j) {
       j["timecode"] = {{"rate", "25"}, {"start", "01:00:00:00"}, {"freewheel_s", -1}};
     },
     "/timecode/freewheel_s", "[0, 3600]"},
    {"timecode_unknown_key",
     [](json& j) {
       j["timecode"] = {{"rate", "25"}, {"start", "01:00:00:00"}, {"offset", 3}};
     },
     "/timecode/offset", "unknown key"},
    {"camera_not_array", [](json& j) { j["camera"] = json::object(); }, "/camera", "must be an array of 1 to"},
    {"camera_empty", [](json& j) { j["camera"] = json::array(); }, "/camera", "must be an array of 1 to"},
    {"camera_key_not_object", [](json& j) { j["camera"][1] = 5; }, "/camera/1", "must be a key object"},
    {"t_s_missing", [](json& j) { j["camera"][1].erase("t_s"); }, "/camera/1/t_s", "missing required key"},
    {"t_s_negative", [](json& j) { j["sun"][0]["t_s"] = -1; }, "/sun/0/t_s", "must be in [0, 86400] s"},
    {"t_s_not_increasing", [](json& j) { j["camera"][1]["t_s"] = 0; }, "/camera/1/t_s", "strictly increasing"},
    {"t_s_not_number", [](json& j) { j["exposure"][1]["t_s"] = "10"; }, "/exposure/1/t_s", "must be a number"},
    {"camera_unknown_body", [](json& j) { j["camera"][0]["surface"]["body"] = "Venus"; }, "/camera/0/surface/body",
     "must be one of \"Earth\""},
    {"camera_unknown_key", [](json& j) { j["camera"][0]["fov"] = 90; }, "/camera/0/fov", "unknown key"},
    {"camera_exposure", [](json& j) { j["camera"][0]["exposure"] = 3; }, "/camera/0/exposure", "its own track"},
    {"camera_two_positions",
     [](json& j) {
       j["camera"][0]["position_m"] = {7e6, 0, 0};
     },
     "/camera/0", "give exactly one of \"position_m\", \"surface\""},
    {"camera_altitude_range", [](json& j) { j["camera"][1]["surface"]["altitude_m"] = 0; },
     "/camera/1/surface/altitude_m", "must be in [0.1"},
    {"camera_surface_keys_too_far",
     [](json& j) {
       j["camera"][1]["surface"]["latitude_deg"] = -45;
       j["camera"][1]["surface"]["longitude_deg"] = 170;
     },
     "/camera/1/surface", "at most 120 deg apart"},
    {"sun_elevation_range", [](json& j) { j["sun"][1]["sky"]["elevation_deg"] = 95; }, "/sun/1/sky/elevation_deg",
     "must be in [-90, 90] deg"},
    {"sun_antipodal",
     [](json& j) {
       j["sun"] = json::array({{{"t_s", 0}, {"direction", {1, 0, 0}}}, {{"t_s", 5}, {"direction", {-1, 0, 0}}}});
     },
     "/sun/1", "less than 179 deg apart"},
    {"sun_zero_direction",
     [](json& j) {
       j["sun"][0] = {{"t_s", 0}, {"direction", {0, 0, 0}}};
     },
     "/sun/0/direction", "must be a non-zero vector"},
    {"exposure_zero", [](json& j) { j["exposure"][0]["exposure"] = 0; }, "/exposure/0/exposure", "(0, 1e+06]"},
    {"exposure_unknown_key", [](json& j) { j["exposure"][0]["value"] = 3; }, "/exposure/0/value", "unknown key"},
    {"atmosphere_unknown_body", [](json& j) { j["atmospheres"][0]["body"] = "Mars"; }, "/atmospheres/0/body",
     "no body of that name with an atmosphere (those with one: \"Earth\")"},
    {"atmosphere_body_twice", [](json& j) { j["atmospheres"][1] = j["atmospheres"][0]; }, "/atmospheres/1/body",
     "already has tracks at /atmospheres/0"},
    {"parameter_missing_in_atmosphere",
     [](json& j) { j["atmospheres"][0]["tracks"][0]["parameter"] = "/aerosol/turbidty"; },
     "/atmospheres/0/tracks/0/parameter", "not present in the parameters of the atmosphere of \"Earth\""},
    {"parameter_not_pointer", [](json& j) { j["atmospheres"][0]["tracks"][0]["parameter"] = "aerosol.turbidity"; },
     "/atmospheres/0/tracks/0/parameter", "must be a JSON pointer"},
    {"parameters_overlap",
     [](json& j) {
       j["atmospheres"][0]["tracks"][1] = {{"parameter", "/aerosol"},
                                           {"keys", json::array({{{"t_s", 0}, {"value", nullptr}}})}};
     },
     "/atmospheres/0/tracks/1/parameter", "overlaps the parameter of track 0"},
    {"step_zero", [](json& j) { j["atmospheres"][0]["tracks"][0]["step"] = 0; }, "/atmospheres/0/tracks/0/step",
     "must be a number > 0"},
    {"step_negative", [](json& j) { j["atmospheres"][0]["tracks"][0]["step"] = -0.5; }, "/atmospheres/0/tracks/0/step",
     "must be a number > 0"},
    {"step_missing", [](json& j) { j["atmospheres"][0]["tracks"][0].erase("step"); }, "/atmospheres/0/tracks/0/step",
     "missing required key"},
    {"step_on_held_track",
     [](json& j) {
       j["atmospheres"][0]["tracks"][0] = {
           {"parameter", "/ozone"}, {"step", 1}, {"keys", json::array({{{"t_s", 0}, {"value", nullptr}}})}};
     },
     "/atmospheres/0/tracks/0/step", "applies to numeric tracks only"},
    {"mixed_value_kinds", [](json& j) { j["atmospheres"][0]["tracks"][0]["keys"][1]["value"] = "3"; },
     "/atmospheres/0/tracks/0/keys/1/value", "must be a number"},
    {"value_missing", [](json& j) { j["atmospheres"][0]["tracks"][0]["keys"][1].erase("value"); },
     "/atmospheres/0/tracks/0/keys/1/value", "missing required key"},
    {"value_out_of_range", [](json& j) { j["atmospheres"][0]["tracks"][0]["keys"][1]["value"] = 100.0; },
     "/atmospheres/0", "does not resolve"},
    {"removing_required_key",
     [](json& j) {
       j["atmospheres"][0]["tracks"][0] = {
           {"parameter", "/gas"},
           {"keys", json::array({{{"t_s", 0}, {"value", json::object()}}, {{"t_s", 5}, {"value", nullptr}}})}};
     },
     "/atmospheres/0", "at show time 0 s"},
    {"recording_with_tracks",
     [](json& j) {
       j["recording"] = {{"fps", 30}, {"versions", json::array()}, {"frames", json::array()}};
     },
     "/fps", "is not used in a recording"},
    {"not_an_object",
     [](json& j) {
       j = json::array({1, 2});
     },
     "", "must be a JSON object"},
};

TEST(ShowErrors, TheValidShowLoads) {
  const auto dir = test::temp_folder("errors_valid");
  EXPECT_NO_THROW(load_show(test::write_file(dir / "valid.json", valid_show().dump(2))));
}

class MalformedShow : public ::testing::TestWithParam<Case> {};

TEST_P(MalformedShow, NamesFileKeyAndReason) {
  const Case& c = GetParam();
  json show = valid_show();
  c.spoil(show);
  const auto path = test::write_file(test::temp_folder(c.name) / "broken.json", show.dump(2));
  try {
    load_show(path);
    FAIL() << c.name << ": accepted";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), path.string()) << what;
    EXPECT_EQ(e.key(), c.key) << what;
    EXPECT_NE(what.find(c.reason), std::string::npos) << what;
    EXPECT_TRUE(what.starts_with(path.string() + ": ")) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, MalformedShow, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& case_info) {
                           return std::string(case_info.param.name);
                         });

TEST(ShowErrors, InvalidJsonNamesTheFile) {
  // JSON has no NaN: such a file fails as JSON, naming the file and the offset.
  const auto dir = test::temp_folder("errors_nan");
  const auto path = test::write_file(dir / "nan.json", R"({"zenith_show": 1, "fps": NaN})");
  try {
    load_show(path);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_NE(std::string(e.what()).find("not valid JSON"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_show(dir / "missing.json"), ConfigError);
}

TEST(ShowErrors, AnInvalidSceneIsReportedUnderTheShowsSceneKey) {
  const auto dir = test::temp_folder("errors_scene");
  test::write_file(dir / "scene.json", R"({"zenith_scene": 1, "name": "x"})");
  json show = valid_show();
  show["scene"] = "scene.json";
  try {
    load_show(test::write_file(dir / "show.json", show.dump()));
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "/scene");
    EXPECT_NE(std::string(e.what()).find("invalid scene file: "), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace zenith::show
