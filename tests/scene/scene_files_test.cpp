// Every scene in configs/scenes/ loads, and the examples show what they say.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>

#include "atmosphere/photometry.h"
#include "core/units.h"
#include "scene/scene_loader.h"
#include "scene/sun_disc.h"

namespace zenith::scene {
namespace {

using glm::dvec3;
namespace fs = std::filesystem;

using core::kDeg;

const fs::path kScenes = fs::path(ZENITH_SOURCE_DIR) / "configs" / "scenes";

std::vector<std::string> scene_files() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kScenes))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

Scene load(const std::string& name) { return load_scene(kScenes / (name + ".json")); }

dvec3 forward_of(const Camera& c) { return c.orientation * dvec3(0, 0, -1); }

double altitude_m(const Scene& s, const std::string& body) {
  const Body* b = s.find_body(body);
  return glm::length(s.camera.position_m - b->position_m) - b->radius_m;
}

/// Elevation of a direction above the camera's local horizon on `body` [deg].
double elevation_deg(const Scene& s, const std::string& body, const dvec3& d) {
  const dvec3 up = glm::normalize(s.camera.position_m - s.find_body(body)->position_m);
  return std::asin(glm::dot(d, up)) / kDeg;
}

/// Angle between the view direction and a world point or direction [deg].
double angle_deg(const dvec3& a, const dvec3& b) {
  return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) / kDeg;
}

class SceneFile : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneFile, LoadsAndIsConsistent) {
  const Scene s = load(GetParam());
  EXPECT_EQ(s.name, GetParam()) << "the scene's name is its file name";
  EXPECT_NO_THROW(check_scene(s));
  EXPECT_FALSE(s.bodies.empty());
  for (const Body& b : s.bodies)
    if (b.atmosphere) {
      EXPECT_TRUE(b.atmosphere->loaded.warnings.empty()) << b.name;
    }
  for (double e : s.sun.irradiance_W_m2_nm) EXPECT_GT(e, 0.1);
}

INSTANTIATE_TEST_SUITE_P(ConfigsScenes, SceneFile, ::testing::ValuesIn(scene_files()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = param_info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(SceneFiles, TheExamplesAreThere) {
  const auto names = scene_files();
  for (const char* expected : {"earth-moon", "earth-ground-noon", "earth-sunset", "earth-orbit-limb", "mars-ground-day",
                               "mars-sunset", "mars-orbit"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
}

TEST(SceneFiles, EarthMoonSeesBothFromTheSide) {
  const Scene s = load("earth-moon");
  const Body& earth = *s.find_body("Earth");
  const Body& moon = *s.find_body("Moon");
  EXPECT_NEAR(glm::length(moon.position_m - earth.position_m), 3.844e8, 1.0);
  EXPECT_NEAR(glm::length(s.camera.position_m - earth.position_m), 2e7, 1e6);
  ASSERT_TRUE(earth.atmosphere);
  EXPECT_EQ(earth.atmosphere->source, "preset:earth-advanced");
  EXPECT_EQ(earth.albedo.procedural, "earth");
  EXPECT_EQ(moon.albedo.procedural, "moon");
  // Both within 45° of the view direction, the Moon clear of Earth's disc.
  const dvec3 f = forward_of(s.camera);
  const dvec3 to_earth = earth.position_m - s.camera.position_m, to_moon = moon.position_m - s.camera.position_m;
  EXPECT_LT(angle_deg(f, to_earth), 45.0);
  EXPECT_LT(angle_deg(f, to_moon), 45.0);
  const double earth_radius_deg = std::asin(earth.radius_m / glm::length(to_earth)) / kDeg;
  EXPECT_GT(angle_deg(to_earth, to_moon), earth_radius_deg + 5.0);
  // Sun from the side: roughly perpendicular to the view.
  EXPECT_NEAR(angle_deg(f, s.sun.direction), 90.0, 25.0);
}

TEST(SceneFiles, GroundAndSunsetScenes) {
  const Scene noon = load("earth-ground-noon");
  EXPECT_NEAR(altitude_m(noon, "Earth"), 2.0, 1e-6);
  EXPECT_GT(elevation_deg(noon, "Earth", noon.sun.direction), 45.0);

  const Scene sunset = load("earth-sunset");
  EXPECT_NEAR(elevation_deg(sunset, "Earth", sunset.sun.direction), 1.0, 1e-9);
  EXPECT_LT(angle_deg(forward_of(sunset.camera), sunset.sun.direction), 15.0);

  const Scene limb = load("earth-orbit-limb");
  EXPECT_NEAR(altitude_m(limb, "Earth"), 4e5, 1e-3);
  // The horizon dips by acos(R / (R + h)); the view and the sun are near it.
  const double dip = std::acos(6371000.0 / (6371000.0 + 4e5)) / kDeg;
  EXPECT_NEAR(elevation_deg(limb, "Earth", forward_of(limb.camera)), -dip, 5.0);
  EXPECT_NEAR(elevation_deg(limb, "Earth", limb.sun.direction), -dip, 1.0);
}

TEST(SceneFiles, MarsScenes) {
  for (const char* name : {"mars-ground-day", "mars-sunset", "mars-orbit"}) {
    const Scene s = load(name);
    const Body& mars = *s.find_body("Mars");
    ASSERT_TRUE(mars.atmosphere) << name;
    EXPECT_EQ(mars.atmosphere->source, "preset:mars");
    EXPECT_EQ(mars.albedo.procedural, "mars");
    // At 1.524 AU: irradiance / 1.524², disc 0.35°.
    EXPECT_NEAR(s.sun.irradiance_W_m2_nm[1] * 1.524 * 1.524, atmosphere::solar_irradiance_W_m2_nm(550.0), 1e-9);
    EXPECT_NEAR(2.0 * s.sun.angular_radius_rad / kDeg, 0.533 / 1.524, 0.001);
  }
  const Scene sunset = load("mars-sunset");
  EXPECT_NEAR(elevation_deg(sunset, "Mars", sunset.sun.direction), 2.0, 1e-9);
  EXPECT_LT(angle_deg(forward_of(sunset.camera), sunset.sun.direction), 15.0);
  const Scene orbit = load("mars-orbit");
  EXPECT_NEAR(glm::length(orbit.camera.position_m), 1e7, 5e5);
  EXPECT_LT(angle_deg(forward_of(orbit.camera), -orbit.camera.position_m), 1e-6);
}

}  // namespace
}  // namespace zenith::scene
