// The operator's changes on top of a show's atmospheres
// (cluster/master/atmosphere_overrides.h; docs/operator.md, "set during a
// show"): applied in order to whatever version the show gives, one change per
// pointer, the base they were last built on, clear.
#include "cluster/master/atmosphere_overrides.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace zenith::cluster {
namespace {

using nlohmann::json;
using test::digest;

operator_command::Set set(const std::string& body, const std::string& pointer, json value) {
  return operator_command::Set{body, json::json_pointer(pointer), std::move(value)};
}

TEST(AtmosphereOverrides, ChangesApplyOnTopOfAnyShowVersionUntilCleared) {
  AtmosphereOverrides overrides;
  const json show_a = {{"aerosol", {{"scattering", {{"turbidity", 2.0}}}, {"scale_height_m", 1200}}},
                       {"ozone", {{"x", 1}}}};
  json show_b = show_a;
  show_b["aerosol"]["scale_height_m"] = 900;  // the show's track moved on
  EXPECT_FALSE(overrides.active("Earth"));
  EXPECT_EQ(overrides.apply("Earth", show_a), show_a);
  EXPECT_EQ(overrides.describe("Earth"), "");

  overrides.add(set("Earth", "/aerosol/scattering/turbidity", 3.0));
  overrides.add(set("Earth", "/ozone", nullptr));
  overrides.add(set("Earth", "/aerosol/scattering/turbidity", 3.5));  // replaces the first, keeps its place
  EXPECT_TRUE(overrides.active("Earth"));
  EXPECT_FALSE(overrides.active("Mars"));
  EXPECT_EQ(overrides.describe("Earth"), "/aerosol/scattering/turbidity = 3.5, /ozone = removed");
  const json a = overrides.apply("Earth", show_a);
  EXPECT_EQ(a["aerosol"]["scattering"]["turbidity"], 3.5);
  EXPECT_FALSE(a.contains("ozone"));
  EXPECT_EQ(a["aerosol"]["scale_height_m"], 1200);
  const json b = overrides.apply("Earth", show_b);
  EXPECT_EQ(b["aerosol"]["scattering"]["turbidity"], 3.5) << "the operator's value wins over the track";
  EXPECT_EQ(b["aerosol"]["scale_height_m"], 900) << "what the operator did not touch follows the track";

  EXPECT_FALSE(overrides.base("Earth"));
  overrides.set_base("Earth", digest(1));
  EXPECT_EQ(overrides.base("Earth"), digest(1));
  overrides.set_base("Mars", digest(2));
  EXPECT_FALSE(overrides.base("Mars")) << "no changes, no base";

  overrides.clear("Earth");
  EXPECT_FALSE(overrides.active("Earth"));
  EXPECT_FALSE(overrides.base("Earth"));
  EXPECT_EQ(overrides.apply("Earth", show_b), show_b);
}

TEST(AtmosphereOverrides, AChangeThatNoLongerFitsTheShowsVersionThrows) {
  AtmosphereOverrides overrides;
  overrides.add(set("Earth", "/ozone/temperature_K", 230));
  EXPECT_THROW(overrides.apply("Earth", json{{"ozone", 3}}), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::cluster
