// Naming an atmosphere and a table size set (atmosphere/named_inputs.h), as the
// commands' --atmosphere and --tables and the cluster config's "table_sizes" do.
#include "atmosphere/named_inputs.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "core/json_reader.h"

namespace zenith::atmosphere {
namespace {

TEST(NamedInputs, TableSizeSetsByName) {
  EXPECT_EQ(table_sizes_by_name("paper"), lut::TableSizes{});
  EXPECT_EQ(table_sizes_by_name("small"), lut::TableSizes::small());
  const lut::TableSizes large = table_sizes_by_name("large");
  EXPECT_EQ(large.describe(), "T512x128 E128x32 S64x256x64x16");
  // The paper's sizes with 128 μs texels (docs/night-sky.md, "Twilight in the tables").
  EXPECT_EQ(table_sizes_by_name("twilight").describe(), "T256x64 E64x16 S32x128x128x8");
  for (const std::string& name : table_size_names()) EXPECT_NO_THROW((void)table_sizes_by_name(name)) << name;
  try {
    (void)table_sizes_by_name("huge");
    FAIL() << "an unknown name must throw";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'huge'"), std::string::npos) << message;
    EXPECT_NE(message.find("paper, twilight, small or large"), std::string::npos) << message;
  }
}

TEST(NamedInputs, ATableSetSetsItsSizesAndRaySamplesAndNothingElse) {
  lut::PrecomputeOptions options;
  options.max_orders = 9;
  options.sphere_zenith_samples = 32;
  apply_table_set("twilight", options);
  EXPECT_EQ(options.sizes, table_sizes_by_name("twilight"));
  EXPECT_EQ(options.scattering_samples, 200);  // 4× the day's: the rays toward the sunlit air below −12°
  EXPECT_EQ(options.max_orders, 9);
  EXPECT_EQ(options.sphere_zenith_samples, 32);
  apply_table_set("paper", options);  // back to the day's samples
  EXPECT_EQ(options.sizes, lut::TableSizes{});
  EXPECT_EQ(options.scattering_samples, lut::PrecomputeOptions{}.scattering_samples);
  EXPECT_EQ(options.max_orders, 9);
  EXPECT_THROW(apply_table_set("huge", options), std::invalid_argument);
}

TEST(NamedInputs, AnAtmosphereByPresetNameOrByFile) {
  const LoadedAtmosphere preset = load_atmosphere_argument("mars");
  const LoadedAtmosphere file =
      load_atmosphere_argument(std::string(ZENITH_SOURCE_DIR) + "/configs/atmospheres/mars.json");
  EXPECT_EQ(preset.model.ground_radius_m, file.model.ground_radius_m);
  EXPECT_EQ(preset.model.rayleigh_scattering_m1, file.model.rayleigh_scattering_m1);
  EXPECT_NE(preset.model.ground_radius_m, load_atmosphere_argument("earth-standard").model.ground_radius_m);
  // A value that looks like a file is read as one: no preset lookup for "mars.json".
  EXPECT_THROW((void)load_atmosphere_argument("no-such-dir/mars.json"), ConfigError);
  EXPECT_THROW((void)load_atmosphere_argument("no-such-preset"), ConfigError);
}

}  // namespace
}  // namespace zenith::atmosphere
