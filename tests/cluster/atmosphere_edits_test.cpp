// The operator's live atmosphere changes (cluster/master/atmosphere_edits.h;
// docs/operator.md, "Live atmosphere parameters"): the atmosphere loader's
// checks and messages, the body check, the waiting queue, and a property test
// of mutated `set` commands against the Earth of earth-sunset.json.
#include "cluster/master/atmosphere_edits.h"

#include <gtest/gtest.h>

#include <random>

#include "atmosphere/model_hash.h"
#include "core/json_reader.h"
#include "scene/scene_loader.h"

namespace zenith::cluster {
namespace {

using nlohmann::json;
namespace oc = operator_command;

const std::filesystem::path kSource = ZENITH_SOURCE_DIR;

class AtmosphereEditsTest : public ::testing::Test {
 protected:
  AtmosphereEditsTest() : scene_(scene::load_scene(kSource / "configs/scenes/earth-sunset.json")), edits_(scene_) {}

  const json& earth_parameters() const { return scene_.bodies[0].atmosphere->loaded.parameters; }
  static oc::Set set(const std::string& body, const std::string& pointer, json value) {
    return oc::Set{body, json::json_pointer(pointer), std::move(value)};
  }
  /// The message of what resolving `s` on Earth's parameters throws ("" if it resolves).
  std::string error_of(const oc::Set& s) const {
    try {
      edits_.resolve(s, earth_parameters());
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  }

  scene::Scene scene_;
  AtmosphereEdits edits_;
};

TEST_F(AtmosphereEditsTest, AChangeIsResolvedAtTheScenesWavelengthsAndMakesANewTableVersion) {
  ASSERT_EQ(edits_.bodies(), std::vector<std::string>{"Earth"});
  const AtmosphereEdits::Edit edit =
      edits_.resolve(set("Earth", "/aerosol/scattering/turbidity", 3.0), earth_parameters());
  EXPECT_EQ(edit.index, 0u);
  EXPECT_EQ(edit.body, "Earth");
  EXPECT_EQ(edit.change, "/aerosol/scattering/turbidity = 3.0");
  EXPECT_EQ(edit.loaded.parameters["aerosol"]["scattering"]["turbidity"], 3.0);
  EXPECT_EQ(edit.loaded.model.wavelengths_nm, scene_.wavelengths_nm);
  EXPECT_NE(atmosphere::lookup_table_hash(edit.loaded.model),
            atmosphere::lookup_table_hash(scene_.bodies[0].atmosphere->loaded.model));
  // Ozone off: null removes the block.
  const AtmosphereEdits::Edit no_ozone = edits_.resolve(set("Earth", "/ozone", nullptr), earth_parameters());
  EXPECT_FALSE(no_ozone.loaded.parameters.contains("ozone"));
  EXPECT_EQ(no_ozone.change, "/ozone = removed");
}

TEST_F(AtmosphereEditsTest, BadValuesGetTheLoadersMessageNamingThePointerAndTheRange) {
  EXPECT_EQ(error_of(set("Earth", "/aerosol/scattering/turbidity", 100)),
            "set Earth: /aerosol/scattering/turbidity = 100: must be in [1, 64]");
  EXPECT_NE(error_of(set("Earth", "/aerosol/scattering/turbidty", 3)).find("/aerosol/scattering/turbidty: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of(set("Earth", "/air_mass", "flat")).find("/air_mass = \"flat\": must be one of"),
            std::string::npos);
  EXPECT_NE(error_of(set("Mars", "/air_mass", "geometric"))
                .find("no body of that name with an atmosphere (bodies with one: 'Earth')"),
            std::string::npos);
  EXPECT_NE(error_of(set("Earth", "/name/x", 1)).find("command: /pointer: /name/x"), std::string::npos);
  // Valid for the loader, but no longer Earth's radius.
  EXPECT_NE(error_of(set("Earth", "/planet/radius_m", 6400000)).find("no longer fits its body"), std::string::npos)
      << error_of(set("Earth", "/planet/radius_m", 6400000));
}

// The scene's wavelengths override the parameters' own,
// so `set /wavelengths_nm/0 "banana"` was ignored and answered ok.
TEST_F(AtmosphereEditsTest, TheWavelengthsAreTheScenesAndCannotBeSet) {
  EXPECT_NE(error_of(set("Earth", "/wavelengths_nm/0", "banana"))
                .find("set Earth: /wavelengths_nm/0 = \"banana\": the wavelengths are the scene's"),
            std::string::npos)
      << error_of(set("Earth", "/wavelengths_nm/0", "banana"));
  EXPECT_NE(error_of(set("Earth", "/wavelengths_nm", json::array({440, 550}))).find("not a live parameter"),
            std::string::npos);
  EXPECT_NE(error_of(set("Earth", "/wavelengths_nm", nullptr)).find("not a live parameter"), std::string::npos);
}

TEST_F(AtmosphereEditsTest, ALaterEditOfTheSameBodyReplacesTheWaitingOneAndKeepsItsPlace) {
  EXPECT_FALSE(edits_.take_next());
  AtmosphereEdits::Edit first = edits_.resolve(set("Earth", "/aerosol/scattering/turbidity", 3.0), earth_parameters());
  edits_.enqueue(first);
  ASSERT_NE(edits_.waiting("Earth"), nullptr);
  // The next change builds on the waiting one's parameters.
  AtmosphereEdits::Edit second =
      edits_.resolve(set("Earth", "/aerosol/scale_height_m", 1500), edits_.waiting("Earth")->loaded.parameters);
  edits_.enqueue(second);
  EXPECT_EQ(edits_.waiting_count(), 1u);
  const auto next = edits_.take_next();
  ASSERT_TRUE(next);
  EXPECT_EQ(next->change, "/aerosol/scattering/turbidity = 3.0, /aerosol/scale_height_m = 1500");
  EXPECT_EQ(next->loaded.parameters["aerosol"]["scattering"]["turbidity"], 3.0);
  EXPECT_EQ(next->loaded.parameters["aerosol"]["scale_height_m"], 1500);
  EXPECT_EQ(edits_.waiting("Earth"), nullptr);
  EXPECT_FALSE(edits_.take_next());
}

TEST_F(AtmosphereEditsTest, AWholeParameterSetTheScenesOwnAndDroppingAWaitingEdit) {
  json changed = earth_parameters();
  changed["aerosol"]["scattering"]["turbidity"] = 4.0;
  const AtmosphereEdits::Edit edit = edits_.resolve_parameters("Earth", changed, "the show's version with turbidity 4");
  EXPECT_EQ(edit.change, "the show's version with turbidity 4");
  EXPECT_EQ(edit.loaded.parameters["aerosol"]["scattering"]["turbidity"], 4.0);
  changed["aerosol"]["scattering"]["turbidity"] = 100;
  EXPECT_THROW(edits_.resolve_parameters("Earth", changed, "too turbid"), ConfigError);

  const AtmosphereEdits::Edit original = edits_.original("Earth");
  EXPECT_EQ(original.change, "the scene's own atmosphere");
  EXPECT_EQ(atmosphere::lookup_table_hash(original.loaded.model),
            atmosphere::lookup_table_hash(scene_.bodies[0].atmosphere->loaded.model));
  EXPECT_THROW(edits_.original("Mars"), std::invalid_argument);

  EXPECT_FALSE(edits_.drop("Earth"));
  edits_.enqueue(edit);
  EXPECT_TRUE(edits_.drop("Earth"));
  EXPECT_EQ(edits_.waiting("Earth"), nullptr);
  EXPECT_FALSE(edits_.take_next());
}

/// Every pointer to a leaf or block of `value`, as "/a/b".
void pointers(const json& value, const std::string& prefix, std::vector<std::string>& out) {
  if (!value.is_structured()) return;
  if (value.is_object())
    for (const auto& [key, child] : value.items()) {
      out.push_back(prefix + "/" + key);
      pointers(child, prefix + "/" + key, out);
    }
  else
    for (std::size_t i = 0; i < value.size(); ++i) {
      out.push_back(prefix + "/" + std::to_string(i));
      pointers(value[i], prefix + "/" + std::to_string(i), out);
    }
}

TEST_F(AtmosphereEditsTest, MutatedSetsResolveOrFailCleanly) {
  std::vector<std::string> paths;
  pointers(earth_parameters(), "", paths);
  paths.insert(paths.end(), {"/aerosol/nope", "/-", "/planet/-", "/sources/-", "/sources/99", "/gas/phase/x"});
  const std::vector<json> values = {nullptr,
                                    true,
                                    0,
                                    -1,
                                    1,
                                    2.5,
                                    64,
                                    1e300,
                                    -1e300,
                                    "",
                                    "penndorf",
                                    "pickering",
                                    json::array(),
                                    json::object(),
                                    json{1, 2},
                                    json{{"680", 0.3}},
                                    1e-300};
  std::mt19937_64 rng(7);
  std::size_t accepted = 0;
  for (int i = 0; i < 3000; ++i) {
    const oc::Set s = set("Earth", paths[rng() % paths.size()], values[rng() % values.size()]);
    try {
      const AtmosphereEdits::Edit edit = edits_.resolve(s, earth_parameters());
      EXPECT_FALSE(atmosphere::lookup_table_hash(edit.loaded.model).empty());
      ++accepted;
    } catch (const ConfigError&) {
    } catch (const std::invalid_argument&) {
    }
  }
  EXPECT_GT(accepted, 10u);
}

}  // namespace
}  // namespace zenith::cluster
