#include "atmosphere/parameters.h"

#include <gtest/gtest.h>

#include <fstream>

#include "atmosphere/mie.h"
#include "atmosphere/model_hash.h"
#include "core/json_reader.h"

namespace zenith::atmosphere {
namespace {

using nlohmann::json;

TEST(Presets, AllLoadAndAreConsistent) {
  const auto names = preset_names();
  for (const char* expected : {"earth-standard", "earth-advanced", "mars", "titan", "halcyon"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  for (const auto& name : names) {
    const LoadedAtmosphere a = load_preset(name);
    EXPECT_NO_THROW(a.model.check()) << name;
    EXPECT_TRUE(a.warnings.empty()) << name << ": " << (a.warnings.empty() ? "" : a.warnings[0]);
    EXPECT_EQ(a.model.wavelengths_nm, kDefaultWavelengths_nm);
  }
}

TEST(Presets, PresetFilesOnDiskMatchTheEmbeddedOnes) {
  for (const auto& name : preset_names()) {
    const auto from_file =
        load_atmosphere_file(std::string(ZENITH_SOURCE_DIR) + "/configs/atmospheres/" + name + ".json");
    EXPECT_EQ(lookup_table_hash(from_file.model), lookup_table_hash(load_preset(name).model)) << name;
  }
}

TEST(Presets, EarthAdvancedRayleighAndOzone) {
  const AtmosphereModel m = load_preset("earth-advanced").model;
  EXPECT_NEAR(m.rayleigh_scattering_m1[0], 4.849e-6, 0.003e-6);
  EXPECT_NEAR(m.rayleigh_scattering_m1[1], 11.483e-6, 0.006e-6);
  EXPECT_NEAR(m.rayleigh_scattering_m1[2], 28.66e-6, 0.015e-6);
  const auto tau = m.zenith_optical_depth();
  ASSERT_EQ(tau.absorbers.size(), 1u);
  EXPECT_EQ(tau.absorbers[0].first, "ozone");
  // Ozone's Chappuis band: strongest at 550 nm, ~0.03 at the zenith; weak at 440 nm.
  EXPECT_NEAR(tau.absorbers[0].second[1], 0.0315, 0.002);
  EXPECT_GT(tau.absorbers[0].second[1], tau.absorbers[0].second[0]);
  EXPECT_LT(tau.absorbers[0].second[2], 0.1 * tau.absorbers[0].second[1]);
  EXPECT_TRUE(m.air_mass.enabled());
}

TEST(Presets, MarsIsDustDominatedWithPhysicalSingleScatteringAlbedo) {
  const AtmosphereModel m = load_preset("mars").model;
  const auto tau = m.zenith_optical_depth();
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_GT(tau.mie_scattering[i], 50.0 * tau.rayleigh[i]);
    // K was chosen so eq. (17) gives ω_ADA β_ext, ω_ADA = 1 − Q_abs/Q_ext.
    const double lambda = m.wavelengths_nm[i];
    const double k = std::vector<double>{0.001, 0.006, 0.013}[i];
    const double ssa = 1.0 - anomalous_diffraction_absorption_efficiency(lambda, k, 1.6e-6) /
                                 anomalous_diffraction_extinction_efficiency(lambda, {1.52, k}, 1.6e-6);
    EXPECT_NEAR(m.mie_scattering_m1[i] / m.mie_extinction_m1[i], ssa, 2e-3) << lambda;
  }
  // CO2 Rayleigh for ~6 hPa: ~2.6e-7 m^-1 at 550 nm (Table 1's value is ~12000x larger).
  EXPECT_NEAR(m.rayleigh_scattering_m1[1], 2.6e-7, 0.1e-7);
  // Blue forward lobe sharper than red: the blue aureole.
  EXPECT_GT(m.mie_phase(2, 1.0), m.mie_phase(0, 1.0));
}

TEST(Parameters, WavelengthOverrideResamplesEverything) {
  LoadOptions o;
  o.wavelengths_nm = std::vector<double>{400, 450, 500, 550, 600, 650, 700};
  const LoadedAtmosphere a = load_preset("earth-advanced", o);
  EXPECT_EQ(a.model.wavelength_count(), 7u);
  for (std::size_t i = 1; i < 7; ++i)
    EXPECT_LT(a.model.rayleigh_scattering_m1[i], a.model.rayleigh_scattering_m1[i - 1]);
  // K is given at 440..680 nm only: 400 and 700 nm use the nearest sample, with a warning.
  EXPECT_FALSE(a.warnings.empty());
  EXPECT_NO_THROW(a.model.check());
}

// ------------------------------------------------------------ malformed input

struct BadCase {
  const char* what;
  const char* json_patch;  // JSON Merge Patch (RFC 7386) applied to earth-advanced
  const char* key;         // the key the error must name
  const char* text;        // a fragment the message must contain
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.what; }

class MalformedAtmosphere : public ::testing::TestWithParam<BadCase> {};

TEST_P(MalformedAtmosphere, IsRejectedNamingTheKey) {
  const BadCase& c = GetParam();
  json params = preset_parameters("earth-advanced");
  params.merge_patch(json::parse(c.json_patch));
  try {
    resolve_atmosphere(params, "bad.json");
    FAIL() << "accepted: " << c.what;
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), "bad.json");
    EXPECT_EQ(e.key(), c.key) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.text), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedAtmosphere,
    ::testing::Values(
        BadCase{"unknown key", R"({"gass": 1})", "/gass", "unknown key"},
        BadCase{"unknown nested key", R"({"aerosol": {"scale_hieght_m": 1}})", "/aerosol/scale_hieght_m",
                "unknown key"},
        BadCase{"missing key", R"({"gas": {"depolarization": null}})", "/gas/depolarization", "missing"},
        BadCase{"missing planet", R"({"planet": null})", "/planet", "missing"},
        BadCase{"negative scale height", R"({"aerosol": {"scale_height_m": -5}})", "/aerosol/scale_height_m",
                "must be in [1, 1e+06] m"},
        BadCase{"negative density", R"({"gas": {"number_density_m3": -2.5e25}})", "/gas/number_density_m3",
                "must be in [1e+10, 1e+30] m^-3"},
        BadCase{"string instead of number", R"({"gas": {"depolarization": "0.03"}})", "/gas/depolarization",
                "must be a number"},
        BadCase{"depolarization out of range", R"({"gas": {"depolarization": 0.9}})", "/gas/depolarization",
                "must be in [0, 0.5]"},
        BadCase{"albedo above one", R"({"planet": {"ground_albedo": {"550": 1.5}}})", "/planet/ground_albedo",
                "must be in [0, 1]"},
        BadCase{"bad wavelength key", R"({"planet": {"ground_albedo": {"green": 0.1}}})", "/planet/ground_albedo",
                "wavelength key"},
        BadCase{"top below ground", R"({"planet": {"atmosphere_height_m": null, "top_radius_m": 6000000}})",
                "/planet/top_radius_m", "below the ground"},
        BadCase{"both heights", R"({"planet": {"top_radius_m": 6500000}})", "/planet", "exactly one"},
        BadCase{"scattering above extinction",
                R"({"aerosol": {"extinction": {"single_scattering_albedo": null, "anomalous_diffraction":
                   {"mean_radius_m": 1e-7, "refractive_index_real": 1.5, "refractive_index_imag": 0.0,
                    "number_density_m3": 1e3}}}})",
                "/aerosol/extinction", "exceeds Mie extinction"},
        BadCase{"turbidity out of range", R"({"aerosol": {"scattering": {"turbidity": 100}}})",
                "/aerosol/scattering/turbidity", "must be in [1, 64]"},
        BadCase{"Junge exponent out of range", R"({"aerosol": {"scattering": {"junge_exponent": 1}}})",
                "/aerosol/scattering/junge_exponent", "must be in [2, 6]"},
        BadCase{"g out of range", R"({"aerosol": {"phase": {"g1": 1.0}}})", "/aerosol/phase/g1", "must be in [-0.999"},
        BadCase{"unknown phase model", R"({"aerosol": {"phase": {"model": "mie"}}})", "/aerosol/phase/model",
                "must be one of"},
        BadCase{"tabulated phase angles not increasing",
                R"({"aerosol": {"phase": {"model": "tabulated", "g1": null, "g2": null, "alpha": null,
                   "scattering_angle_deg": [0, 90, 80, 180], "values": {"550": [4, 1, 1, 1]}}}})",
                "/aerosol/phase/scattering_angle_deg", "[2] = 80: must be greater than the angle before it"},
        BadCase{"tabulated phase short of 180 degrees",
                R"({"aerosol": {"phase": {"model": "tabulated", "g1": null, "g2": null, "alpha": null,
                   "scattering_angle_deg": [0, 90], "values": {"550": [4, 1]}}}})",
                "/aerosol/phase/scattering_angle_deg", "must start at 0 and end at 180"},
        BadCase{"tabulated phase value not positive",
                R"({"aerosol": {"phase": {"model": "tabulated", "g1": null, "g2": null, "alpha": null,
                   "scattering_angle_deg": [0, 90, 180], "values": {"550": [4, 0, 1]}}}})",
                "/aerosol/phase/values", "[\"550\"][1] = 0: must be a finite number > 0"},
        BadCase{"tabulated phase column too short",
                R"({"aerosol": {"phase": {"model": "tabulated", "g1": null, "g2": null, "alpha": null,
                   "scattering_angle_deg": [0, 90, 180], "values": {"550": [4, 1]}}}})",
                "/aerosol/phase/values", "must be an array of 3 values"},
        BadCase{"unknown mode", R"({"mode": "expert"})", "/mode", "must be one of"},
        BadCase{"wrong version", R"({"zenith_atmosphere": 2})", "/zenith_atmosphere", "must be in [1, 1]"},
        BadCase{"ozone temperature outside table", R"({"ozone": {"temperature_K": 200}})", "/ozone/temperature_K",
                "must be in [233, 293] K"},
        BadCase{"empty wavelengths", R"({"wavelengths_nm": []})", "/wavelengths_nm", "array of 1 to 64"},
        BadCase{"duplicate wavelength", R"({"wavelengths_nm": [550, 550]})", "/wavelengths_nm", "twice"},
        BadCase{"scale height needs gravity", R"({"gas": {"scale_height_m": null, "temperature_K": 288}})",
                "/gas/scale_height_m", "surface_gravity"},
        BadCase{"pressure without temperature", R"({"gas": {"number_density_m3": null, "pressure_Pa": 101325}})",
                "/gas/temperature_K", "missing"}),
    [](const auto& test_info) {
      std::string n = test_info.param.what;
      for (char& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

TEST(Parameters, StandardModeScatteringAboveExtinctionIsRejected) {
  json params = preset_parameters("earth-standard");
  params["mie"]["extinction_m1"] = 4.0e-6;  // Table 1's 0.1 × β_M^scat
  try {
    resolve_atmosphere(params, "table1.json");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "/mie/scattering_m1");
    EXPECT_NE(std::string(e.what()).find("exceeds"), std::string::npos);
  }
}

TEST(Parameters, NaNAndInfinityAreRejected) {
  // JSON has no NaN literal; nlohmann turns NaN into null, and huge literals into inf.
  json params = preset_parameters("earth-standard");
  params["rayleigh"]["scale_height_m"] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(resolve_atmosphere(params, "nan.json"), ConfigError);
  EXPECT_THROW(resolve_atmosphere(parse_json(R"({"zenith_atmosphere": 1e999})", "inf.json"), "inf.json"), ConfigError);
}

TEST(Parameters, SyntaxErrorsAndNonObjectsAreConfigErrors) {
  EXPECT_THROW(parse_json("{\"a\": ", "broken.json"), ConfigError);
  for (const char* text : {"[]", "42", "null", "\"text\"", "{}", R"({"zenith_atmosphere": 1})"})
    EXPECT_THROW(resolve_atmosphere(json::parse(text), "x.json"), ConfigError) << text;
}

TEST(Parameters, MissingFileNamesTheFile) {
  try {
    load_atmosphere_file("/nonexistent/atmosphere.json");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/atmosphere.json");
  }
}

TEST(Parameters, UnknownPresetListsTheAvailableOnes) {
  try {
    load_preset("venus");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("earth-standard"), std::string::npos);
  }
}

// ------------------------------------------------------------ identity

TEST(LookupTableHash, IgnoresNameAndKeyOrderButNotPhysics) {
  const json base = preset_parameters("mars");
  const std::string h = lookup_table_hash(resolve_atmosphere(base, "a").model);
  EXPECT_EQ(h.size(), 64u);

  json renamed = base;
  renamed["name"] = "Another name";
  EXPECT_EQ(lookup_table_hash(resolve_atmosphere(renamed, "b").model), h);

  // Re-serialize with keys in reverse order at every level.
  std::function<json(const json&)> reverse = [&](const json& j) -> json {
    if (!j.is_object()) return j;
    std::string text = "{";
    std::vector<std::pair<std::string, json>> items;
    for (auto it = j.begin(); it != j.end(); ++it) items.emplace_back(it.key(), reverse(it.value()));
    for (auto it = items.rbegin(); it != items.rend(); ++it)
      text += (text.size() > 1 ? "," : "") + json(it->first).dump() + ":" + it->second.dump();
    return json::parse(text + "}");
  };
  EXPECT_EQ(lookup_table_hash(resolve_atmosphere(reverse(base), "c").model), h);

  json hazier = base;
  hazier["aerosol"]["scattering"]["turbidity"] = 2.01;
  hazier["aerosol"]["extinction"]["anomalous_diffraction"]["number_density_m3"] = 3e6;
  EXPECT_NE(lookup_table_hash(resolve_atmosphere(hazier, "d").model), h);

  json brighter_ground = base;
  brighter_ground["planet"]["ground_albedo"] = 0.3;
  EXPECT_NE(lookup_table_hash(resolve_atmosphere(brighter_ground, "e").model), h);
}

TEST(LookupTableHash, KnownValueIsStableAcrossMachines) {
  // If this changes, either the canonical description or a preset changed:
  // bump kLookupTableFormatVersion when table semantics change, and update here.
  const std::string text = canonical_description(load_preset("earth-standard").model);
  EXPECT_NE(text.find("rayleigh.scattering_m1: 5.17680000000e-06 1.22588000000e-05 3.05964000000e-05"),
            std::string::npos)
      << text;
  EXPECT_EQ(lookup_table_hash(load_preset("earth-standard").model),
            "6f92a2b2f13a3f6cba9d3a4d3afac23687412d993d331fc2b2d5086e70d54a84");
}

}  // namespace
}  // namespace zenith::atmosphere
