#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include <glm/geometric.hpp>

#include "atmosphere/photometry.h"
#include "core/json_reader.h"
#include "core/units.h"
#include "scene/sun_disc.h"
#include "tests/scratch_folder.h"

namespace zenith::scene {
namespace {

using glm::dvec3;
using nlohmann::json;
namespace fs = std::filesystem;

using core::kDeg;
using core::kPi;

/// A folder of its own for files the tests write, removed when the test process ends.
fs::path test_dir() {
  const fs::path dir = zenith::testing::process_scratch_folder() / "scene";
  fs::create_directories(dir);
  return dir;
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// A valid scene: Earth (earth-standard atmosphere) and the Moon, a camera on
/// Earth looking east, the sun given in the camera's sky.
json base_scene() {
  return json::parse(R"({
    "zenith_scene": 1,
    "name": "test",
    "bodies": [
      {"name": "Earth", "atmosphere": "earth-standard", "albedo": 0.3},
      {"name": "Moon", "radius_m": 1.7374e6, "position_m": [3.844e8, 0, 0],
       "albedo": {"procedural": "moon", "seed": 3, "width_px": 64, "height_px": 32}}
    ],
    "sun": {"sky": {"elevation_deg": 30, "azimuth_deg": 120}},
    "camera": {
      "surface": {"body": "Earth", "latitude_deg": 45, "longitude_deg": 10, "altitude_m": 2},
      "look": {"azimuth_deg": 90, "elevation_deg": 10},
      "exposure": 10
    }
  })");
}

Scene parse(const json& j) { return parse_scene(j, "scene-under-test.json", test_dir()); }

dvec3 forward_of(const Camera& c) { return c.orientation * dvec3(0, 0, -1); }
dvec3 up_of(const Camera& c) { return c.orientation * dvec3(0, 1, 0); }
dvec3 right_of(const Camera& c) { return c.orientation * dvec3(1, 0, 0); }

/// Elevation and azimuth of a direction, measured in the horizon frame of a
/// point above a body (independently of the loader's code path).
struct SkyAngles {
  double elevation_deg, azimuth_deg;
};
SkyAngles measure(const dvec3& d, const dvec3& point, const Body& body) {
  const dvec3 up = glm::normalize(point - body.position_m);
  const dvec3 pole = body.orientation * dvec3(0, 0, 1);
  const dvec3 north = glm::normalize(pole - glm::dot(pole, up) * up);
  const dvec3 east = glm::cross(north, up);
  double az = std::atan2(glm::dot(d, east), glm::dot(d, north)) / kDeg;
  if (az < 0) az += 360.0;
  return {std::asin(std::clamp(glm::dot(d, up), -1.0, 1.0)) / kDeg, az};
}

// ------------------------------------------------------------------ valid scenes

TEST(SceneLoader, BaseSceneResolves) {
  const Scene s = parse(base_scene());
  EXPECT_EQ(s.name, "test");
  EXPECT_EQ(s.source, fs::path("scene-under-test.json"));
  EXPECT_EQ(s.wavelengths_nm, (std::vector<double>{680, 550, 440}));
  ASSERT_EQ(s.bodies.size(), 2u);
  const Body& earth = s.bodies[0];
  EXPECT_EQ(earth.radius_m, 6371000.0);  // from the atmosphere
  ASSERT_TRUE(earth.atmosphere.has_value());
  EXPECT_EQ(earth.atmosphere->source, "preset:earth-standard");
  EXPECT_EQ(earth.albedo.kind, AlbedoSource::Kind::constant);
  EXPECT_EQ(earth.albedo.colour_linear_rgb, dvec3(0.3));
  const Body& moon = s.bodies[1];
  EXPECT_FALSE(moon.atmosphere.has_value());
  EXPECT_EQ(moon.albedo.kind, AlbedoSource::Kind::procedural);
  EXPECT_EQ(moon.albedo.procedural, "moon");
  EXPECT_EQ(moon.albedo.seed, 3u);
  EXPECT_EQ(moon.albedo.width_px, 64);
  EXPECT_EQ(s.find_body("Moon"), &s.bodies[1]);
  EXPECT_EQ(s.find_body("Mars"), nullptr);
  EXPECT_DOUBLE_EQ(s.camera.exposure, 10.0);
  EXPECT_NO_THROW(check_scene(s));
}

TEST(SceneLoader, CameraOnTheSurfaceIsAtRadiusPlusAltitudeAtItsLatitudeAndLongitude) {
  struct Case {
    double lat, lon, alt;
  };
  for (const Case c :
       {Case{45, 10, 2}, Case{-33.9, 151.2, 0.5}, Case{0, -180, 4e5}, Case{89.9, 45, 1e7}, Case{-90, 0, 100}}) {
    json j = base_scene();
    j["bodies"][0]["position_m"] = {1e3, -2e3, 3e3};
    j["camera"]["surface"] = {
        {"body", "Earth"}, {"latitude_deg", c.lat}, {"longitude_deg", c.lon}, {"altitude_m", c.alt}};
    j["camera"].erase("look");
    j["camera"]["forward"] = {0.3, 0.2, -0.1};
    const Scene s = parse(j);
    const double r = 6371000.0 + c.alt, phi = c.lat * kDeg, lambda = c.lon * kDeg;
    const dvec3 expected = dvec3(1e3, -2e3, 3e3) +
                           r * dvec3(std::cos(phi) * std::cos(lambda), std::cos(phi) * std::sin(lambda), std::sin(phi));
    EXPECT_NEAR(glm::length(s.camera.position_m - expected), 0.0, 1e-6 * r) << c.lat << " " << c.lon;
    EXPECT_NEAR(glm::length(s.camera.position_m - dvec3(1e3, -2e3, 3e3)), r, 1e-6);

    // The same point on a body turned 30° about its pole is 30° further east in the world.
    j["bodies"][0]["orientation"] = {{"axis", {0, 0, 1}}, {"angle_deg", 30}};
    const Scene turned = parse(j);
    const double lambda2 = (c.lon + 30.0) * kDeg;
    const dvec3 expected2 = dvec3(1e3, -2e3, 3e3) + r * dvec3(std::cos(phi) * std::cos(lambda2),
                                                              std::cos(phi) * std::sin(lambda2), std::sin(phi));
    EXPECT_NEAR(glm::length(turned.camera.position_m - expected2), 0.0, 1e-6 * r) << c.lat << " " << c.lon;
  }
}

TEST(SceneLoader, NorthPoleAndPrimeMeridianOrientation) {
  json j = base_scene();
  // Pole along world +x, prime meridian along world +y (given slightly off
  // perpendicular: it is projected), so the body's +y (90° E) is world +z.
  j["bodies"][0]["orientation"] = {{"north_pole", {2, 0, 0}}, {"prime_meridian", {0.1, 1, 0}}};
  auto camera_at = [&](double lat, double lon) {
    json k = j;
    k["camera"]["surface"]["latitude_deg"] = lat;
    k["camera"]["surface"]["longitude_deg"] = lon;
    return glm::normalize(parse(k).camera.position_m);
  };
  EXPECT_NEAR(glm::length(camera_at(90, 0) - dvec3(1, 0, 0)), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(camera_at(0, 0) - dvec3(0, 1, 0)), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(camera_at(0, 90) - dvec3(0, 0, 1)), 0.0, 1e-9);
}

TEST(SceneLoader, SunSkyAnglesAreReproducedFromTheResolvedVectors) {
  for (double lat : {45.0, -60.0, 0.0, 10.0})
    for (double lon : {10.0, -120.0})
      for (double el : {-5.0, 1.0, 30.0, 89.0})
        for (double az : {0.0, 90.0, 200.0, 359.0}) {
          json j = base_scene();
          j["bodies"][0]["orientation"] = {{"axis", {1, 0.5, 0}}, {"angle_deg", 23.44}};
          j["camera"]["surface"]["latitude_deg"] = lat;
          j["camera"]["surface"]["longitude_deg"] = lon;
          j["sun"]["sky"] = {{"elevation_deg", el}, {"azimuth_deg", az}};
          const Scene s = parse(j);
          EXPECT_NEAR(glm::length(s.sun.direction), 1.0, 1e-12);
          const SkyAngles m = measure(s.sun.direction, s.camera.position_m, s.bodies[0]);
          EXPECT_NEAR(m.elevation_deg, el, 1e-9);
          EXPECT_NEAR(std::remainder(m.azimuth_deg - az, 360.0), 0.0, 1e-7) << lat << " " << lon << " " << el;
        }
}

TEST(SceneLoader, HorizonFrameAxesAtTheEquatorAndPrimeMeridian) {
  // At latitude 0, longitude 0 of an unrotated body: up = +x, north = +z, east = +y.
  json j = base_scene();
  j["camera"]["surface"]["latitude_deg"] = 0;
  j["camera"]["surface"]["longitude_deg"] = 0;
  auto sun = [&](double el, double az) {
    j["sun"]["sky"] = {{"elevation_deg", el}, {"azimuth_deg", az}};
    return parse(j).sun.direction;
  };
  EXPECT_NEAR(glm::length(sun(0, 0) - dvec3(0, 0, 1)), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(sun(0, 90) - dvec3(0, 1, 0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(sun(0, 180) - dvec3(0, 0, -1)), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(sun(90, 0) - dvec3(1, 0, 0)), 0.0, 1e-12);
  // At the north pole north is the limit along the prime meridian: body −x.
  j["camera"]["surface"]["latitude_deg"] = 90;
  EXPECT_NEAR(glm::length(sun(0, 0) - dvec3(-1, 0, 0)), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(sun(0, 90) - dvec3(0, 1, 0)), 0.0, 1e-9);
}

TEST(SceneLoader, LookAzimuthElevationGiveTheForwardAndALevelHorizon) {
  for (double az : {0.0, 45.0, 90.0, 270.0})
    for (double el : {-30.0, 0.0, 10.0, 60.0}) {
      json j = base_scene();
      j["camera"]["look"] = {{"azimuth_deg", az}, {"elevation_deg", el}};
      const Scene s = parse(j);
      const Camera& c = s.camera;
      const SkyAngles m = measure(forward_of(c), c.position_m, s.bodies[0]);
      EXPECT_NEAR(m.elevation_deg, el, 1e-9);
      EXPECT_NEAR(std::remainder(m.azimuth_deg - az, 360.0), 0.0, 1e-7);
      const dvec3 zenith = glm::normalize(c.position_m - s.bodies[0].position_m);
      EXPECT_NEAR(glm::dot(right_of(c), zenith), 0.0, 1e-12);                                   // level horizon
      EXPECT_NEAR(glm::dot(up_of(c), zenith), std::cos(el * kDeg), 1e-12);                      // zenith tilted by el
      EXPECT_NEAR(glm::length(glm::cross(right_of(c), up_of(c)) + forward_of(c)), 0.0, 1e-12);  // right-handed
    }
}

TEST(SceneLoader, LookRollBanksTheCameraToTheRight) {
  json j = base_scene();
  j["camera"]["look"] = {{"azimuth_deg", 90}, {"elevation_deg", 0}, {"roll_deg", 90}};
  const Scene s = parse(j);
  const dvec3 zenith = glm::normalize(s.camera.position_m - s.bodies[0].position_m);
  // Rolled 90° right: the camera's up is level, its right points to the ground.
  EXPECT_NEAR(glm::dot(up_of(s.camera), zenith), 0.0, 1e-12);
  EXPECT_NEAR(glm::dot(right_of(s.camera), zenith), -1.0, 1e-12);
}

TEST(SceneLoader, LookAtAndForwardWithUp) {
  json j = base_scene();
  j["camera"] = {{"position_m", {2e7, 0, 0}}, {"look_at", {0, 0, 0}}, {"up", {0, 0, 1}}};
  Scene s = parse(j);
  EXPECT_NEAR(glm::length(forward_of(s.camera) - dvec3(-1, 0, 0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(up_of(s.camera) - dvec3(0, 0, 1)), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.camera.exposure, 10.0);  // default

  // Without up, looking straight down at Earth: the body's north pole is up.
  j["camera"].erase("up");
  s = parse(j);
  EXPECT_NEAR(glm::length(up_of(s.camera) - dvec3(0, 0, 1)), 0.0, 1e-12);

  // A forward vector, up not perpendicular: up is made perpendicular.
  j["camera"] = {{"position_m", {2e7, 0, 0}}, {"forward", {-1, 1, 0}}, {"up", {0, 1, 1}}};
  s = parse(j);
  EXPECT_NEAR(glm::length(forward_of(s.camera) - glm::normalize(dvec3(-1, 1, 0))), 0.0, 1e-12);
  EXPECT_NEAR(glm::dot(up_of(s.camera), forward_of(s.camera)), 0.0, 1e-12);
  EXPECT_GT(glm::dot(up_of(s.camera), dvec3(0, 0, 1)), 0.5);
  EXPECT_NEAR(glm::length(s.camera.orientation), 1.0, 1e-12);
}

TEST(SceneLoader, SunDistanceSetsDiameterAndIrradiance) {
  json j = base_scene();
  Scene s = parse(j);
  EXPECT_NEAR(2.0 * s.sun.angular_radius_rad / kDeg, 0.533, 0.0005);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_DOUBLE_EQ(s.sun.irradiance_W_m2_nm[i], atmosphere::solar_irradiance_W_m2_nm(s.wavelengths_nm[i]));

  j["sun"]["distance_au"] = 1.524;
  s = parse(j);
  EXPECT_NEAR(s.sun.angular_radius_rad, std::asin(kSolarRadius_m / (1.524 * kAstronomicalUnit_m)), 1e-15);
  EXPECT_NEAR(s.sun.irradiance_W_m2_nm[1] * 1.524 * 1.524, atmosphere::solar_irradiance_W_m2_nm(550), 1e-12);

  j["sun"]["irradiance"] = 0.5;
  j["sun"]["angular_diameter_deg"] = 2.0;
  s = parse(j);
  EXPECT_NEAR(s.sun.irradiance_W_m2_nm[1] * 1.524 * 1.524 / 0.5, atmosphere::solar_irradiance_W_m2_nm(550), 1e-12);
  EXPECT_NEAR(s.sun.angular_radius_rad, 1.0 * kDeg, 1e-15);

  j["sun"]["irradiance"] = {{"400", 1.0}, {"700", 2.5}};
  s = parse(j);
  EXPECT_NEAR(s.sun.irradiance_W_m2_nm[1], 1.0 + 1.5 * 150.0 / 300.0, 1e-12);  // not scaled by the distance

  // A sun at a point: direction and distance from the camera.
  j = base_scene();
  j["sun"] = {{"position_m", {0, 0, 2.0 * kAstronomicalUnit_m}}};
  s = parse(j);
  const dvec3 d = dvec3(0, 0, 2.0 * kAstronomicalUnit_m) - s.camera.position_m;
  EXPECT_NEAR(glm::length(s.sun.direction - glm::normalize(d)), 0.0, 1e-12);
  EXPECT_NEAR(s.sun.irradiance_W_m2_nm[0],
              atmosphere::solar_irradiance_W_m2_nm(680) / std::pow(glm::length(d) / kAstronomicalUnit_m, 2), 1e-9);

  j["sun"] = {{"direction", {0, 0, 5}}};
  s = parse(j);
  EXPECT_EQ(s.sun.direction, dvec3(0, 0, 1));
}

TEST(SceneLoader, CustomWavelengthsReachAtmospheresAndSun) {
  json j = base_scene();
  j["wavelengths_nm"] = {400, 450, 500, 550, 600, 650, 700};
  const Scene s = parse(j);
  EXPECT_EQ(s.bodies[0].atmosphere->loaded.model.wavelengths_nm, s.wavelengths_nm);
  EXPECT_EQ(s.sun.irradiance_W_m2_nm.size(), 7u);
}

TEST(SceneLoader, AtmosphereFormsAndFiles) {
  const fs::path dir = test_dir();
  fs::create_directories(dir / "maps");
  write_file(dir / "maps" / "ground.png", "not read at load");
  const json parameters = atmosphere::preset_parameters("mars");
  write_file(dir / "my-mars.json", parameters.dump(2));

  json j = base_scene();
  j["bodies"][0] = {
      {"name", "Mars"}, {"atmosphere", {{"file", "my-mars.json"}}}, {"albedo", {{"image", "maps/ground.png"}}}};
  j["bodies"][1]["atmosphere"] = {{"parameters", parameters}};
  j["bodies"][1].erase("radius_m");
  j["camera"]["surface"]["body"] = "Mars";
  const Scene s = parse(j);
  EXPECT_EQ(s.bodies[0].radius_m, 3389500.0);
  EXPECT_EQ(s.bodies[0].atmosphere->source, (dir / "my-mars.json").lexically_normal().string());
  EXPECT_EQ(s.bodies[0].albedo.kind, AlbedoSource::Kind::image);
  EXPECT_EQ(s.bodies[0].albedo.image_path, (dir / "maps" / "ground.png").lexically_normal());
  EXPECT_TRUE(s.bodies[0].albedo.image_path.is_absolute());
  EXPECT_EQ(s.bodies[1].atmosphere->source, "inline");
  EXPECT_EQ(s.bodies[1].radius_m, 3389500.0);

  // Radius given and within 1 m of the atmosphere's: accepted.
  j["bodies"][1]["radius_m"] = 3389500.5;
  EXPECT_EQ(parse(j).bodies[1].radius_m, 3389500.5);
}

TEST(SceneLoader, LoadSceneReadsAFileAndResolvesPathsAgainstItsFolder) {
  const fs::path dir = test_dir() / "sub";
  fs::create_directories(dir);
  write_file(dir / "map.exr", "x");
  json j = base_scene();
  j["bodies"][1]["albedo"] = {{"image", "map.exr"}};
  write_file(dir / "scene.json", j.dump());
  const Scene s = load_scene(dir / "scene.json");
  EXPECT_EQ(s.source, dir / "scene.json");
  EXPECT_EQ(s.bodies[1].albedo.image_path, (dir / "map.exr").lexically_normal());

  write_file(dir / "broken.json", "{\"zenith_scene\": 1,");
  try {
    load_scene(dir / "broken.json");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("not valid JSON"), std::string::npos);
  }
  EXPECT_THROW(load_scene(dir / "absent.json"), ConfigError);
}

TEST(SceneLoader, CheckSceneRejectsBadScenesBuiltInCode) {
  Scene s = parse(base_scene());
  EXPECT_NO_THROW(check_scene(s));
  Scene bad = s;
  bad.camera.orientation = glm::dquat(2, 0, 0, 0);
  EXPECT_THROW(check_scene(bad), std::invalid_argument);
  bad = s;
  bad.bodies[1].position_m = dvec3(1e6, 0, 0);
  EXPECT_THROW(check_scene(bad), std::invalid_argument);
  bad = s;
  bad.sun.irradiance_W_m2_nm.pop_back();
  EXPECT_THROW(check_scene(bad), std::invalid_argument);
  bad = s;
  bad.camera.position_m = s.bodies[0].position_m;
  EXPECT_THROW(check_scene(bad), std::invalid_argument);
}

// ------------------------------------------------------------------ malformed scenes

struct Malformed {
  const char* what;
  std::function<void(json&)> edit;
  const char* pointer;  ///< must appear in the message
  const char* detail;   ///< must appear in the message too ("" for none)
};

void PrintTo(const Malformed& m, std::ostream* os) { *os << m.what; }

class MalformedScene : public ::testing::TestWithParam<Malformed> {};

TEST_P(MalformedScene, IsRejectedNamingTheFileAndTheKey) {
  json j = base_scene();
  GetParam().edit(j);
  try {
    parse_scene(j, "bad-scene.json", test_dir());
    FAIL() << "accepted: " << GetParam().what;
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_TRUE(what.starts_with("bad-scene.json: ")) << what;
    EXPECT_NE(what.find(GetParam().pointer), std::string::npos) << what;
    EXPECT_NE(what.find(GetParam().detail), std::string::npos) << what;
  }
}

json nine_planets_with_atmospheres() {
  json bodies = json::array();
  for (int i = 0; i < 9; ++i)
    bodies.push_back(
        {{"name", std::string(1, char('A' + i))}, {"atmosphere", "mars"}, {"position_m", {1e8 * i, 0, 0}}});
  return bodies;
}

const double kNaN = std::numeric_limits<double>::quiet_NaN();

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedScene,
    ::testing::Values(
        Malformed{"unknown top-level key", [](json& j) { j["camra"] = 1; }, "/camra", "unknown key"},
        Malformed{"unknown body key", [](json& j) { j["bodies"][1]["radius"] = 1; }, "/bodies/1/radius", "unknown key"},
        Malformed{"unknown camera key", [](json& j) { j["camera"]["fov_deg"] = 90; }, "/camera/fov_deg", "allowed here"},
        Malformed{"name of wrong type", [](json& j) { j["name"] = 5; }, "/name", "must be a string"},
        Malformed{"position of wrong type", [](json& j) { j["bodies"][1]["position_m"] = "far"; },
                  "/bodies/1/position_m", "array of 3 numbers"},
        Malformed{"position with 2 numbers", [](json& j) { j["bodies"][1]["position_m"] = {1, 2}; },
                  "/bodies/1/position_m", "array of 3 numbers"},
        Malformed{"no bodies key", [](json& j) { j.erase("bodies"); }, "/bodies", "missing required key"},
        Malformed{"empty bodies", [](json& j) { j["bodies"] = json::array(); }, "/bodies", "1 to 64"},
        Malformed{"camera on a missing body", [](json& j) { j["camera"]["surface"]["body"] = "Mars"; },
                  "/camera/surface/body", "\"Earth\", \"Moon\""},
        Malformed{"overlapping bodies", [](json& j) { j["bodies"][1]["position_m"] = {7e6, 0, 0}; }, "/bodies/1",
                  "intersects body \"Earth\" (/bodies/0)"},
        Malformed{"camera inside a body",
                  [](json& j) {
                    j["camera"] = {{"position_m", {3.844e8 - 1e3, 0, 0}}, {"forward", {1, 0, 0}}};
                  },
                  "/camera/position_m", "inside body \"Moon\""},
        Malformed{"camera on the surface inside another body",
                  [](json& j) {
                    j["bodies"][1]["position_m"] = {0, 0, 6371000 + 1737400 + 1};
                    j["camera"]["surface"] = {{"body", "Earth"}, {"latitude_deg", 90}, {"longitude_deg", 0},
                                              {"altitude_m", 10}};
                  },
                  "/camera/surface", "inside body \"Moon\""},
        Malformed{"radius differs from the atmosphere's", [](json& j) { j["bodies"][0]["radius_m"] = 6.3e6; },
                  "/bodies/0/radius_m", "within 1 m"},
        Malformed{"no radius and no atmosphere", [](json& j) { j["bodies"][1].erase("radius_m"); },
                  "/bodies/1/radius_m", "missing"},
        Malformed{"zero radius", [](json& j) { j["bodies"][1]["radius_m"] = 0; }, "/bodies/1/radius_m",
                  "must be in [1, 1e+09] m"},
        Malformed{"bad preset name", [](json& j) { j["bodies"][0]["atmosphere"] = "venus"; }, "/bodies/0/atmosphere",
                  "earth-advanced"},
        Malformed{"bad preset name (object form)", [](json& j) { j["bodies"][0]["atmosphere"] = {{"preset", "venus"}}; },
                  "/bodies/0/atmosphere/preset", "\"venus\""},
        Malformed{"missing atmosphere file", [](json& j) { j["bodies"][0]["atmosphere"] = {{"file", "nope.json"}}; },
                  "/bodies/0/atmosphere/file", "file not found"},
        Malformed{"inline atmosphere with a bad value",
                  [](json& j) {
                    json p = atmosphere::preset_parameters("earth-standard");
                    p["planet"]["radius_m"] = -5;
                    j["bodies"][0]["atmosphere"] = {{"parameters", p}};
                  },
                  "/bodies/0/atmosphere/parameters/planet/radius_m", "= -5: must be in"},
        Malformed{"missing image file", [](json& j) { j["bodies"][1]["albedo"] = {{"image", "missing/moon.png"}}; },
                  "/bodies/1/albedo/image", "file not found"},
        Malformed{"unknown generator", [](json& j) { j["bodies"][1]["albedo"]["procedural"] = "venus"; },
                  "/bodies/1/albedo/procedural", "\"checker\""},
        Malformed{"negative seed", [](json& j) { j["bodies"][1]["albedo"]["seed"] = -1; }, "/bodies/1/albedo/seed",
                  "[0, 4294967295]"},
        Malformed{"albedo above 1", [](json& j) { j["bodies"][0]["albedo"] = 1.5; }, "/bodies/0/albedo",
                  "must be in [0, 1]"},
        Malformed{"negative exposure", [](json& j) { j["camera"]["exposure"] = -1; }, "/camera/exposure",
                  "= -1: must be in (0, 1e+06]"},
        Malformed{"NaN elevation", [](json& j) { j["sun"]["sky"]["elevation_deg"] = kNaN; }, "/sun/sky/elevation_deg",
                  "must be"},
        Malformed{"NaN in a position", [](json& j) { j["bodies"][1]["position_m"] = {kNaN, 0, 0}; },
                  "/bodies/1/position_m", "must be"},
        Malformed{"infinite exposure", [](json& j) { j["camera"]["exposure"] = std::numeric_limits<double>::infinity(); },
                  "/camera/exposure", "must be"},
        Malformed{"duplicate body names", [](json& j) { j["bodies"][1]["name"] = "Earth"; }, "/bodies/1/name",
                  "duplicate body name (also /bodies/0/name)"},
        Malformed{"empty body name", [](json& j) { j["bodies"][1]["name"] = ""; }, "/bodies/1/name", "empty"},
        Malformed{"format version 2", [](json& j) { j["zenith_scene"] = 2; }, "/zenith_scene", "version 1"},
        Malformed{"no format version", [](json& j) { j.erase("zenith_scene"); }, "/zenith_scene", "missing"},
        Malformed{"wavelength out of range", [](json& j) { j["wavelengths_nm"] = {680, 900}; }, "/wavelengths_nm/1",
                  "must be in [360, 830] nm"},
        Malformed{"wavelengths not monotonic", [](json& j) { j["wavelengths_nm"] = {550, 680, 440}; },
                  "/wavelengths_nm", "increasing or strictly decreasing"},
        Malformed{"two sun directions",
                  [](json& j) { j["sun"]["direction"] = {0, 0, 1}; }, "/sun", "exactly one of"},
        Malformed{"no sun direction", [](json& j) { j["sun"] = json::object(); }, "/sun", "(none given)"},
        Malformed{"sun disc too large", [](json& j) { j["sun"]["angular_diameter_deg"] = 40; },
                  "/sun/angular_diameter_deg", "(0, 30] deg"},
        Malformed{"zero sun direction", [](json& j) { j["sun"] = {{"direction", {0, 0, 0}}}; }, "/sun/direction",
                  "non-zero"},
        Malformed{"sun too close", [](json& j) { j["sun"] = {{"position_m", {0, 0, 1e9}}}; }, "/sun/position_m",
                  "AU"},
        Malformed{"sun distance with position",
                  [](json& j) { j["sun"] = {{"position_m", {0, 0, 1.5e11}}, {"distance_au", 1}}; }, "/sun/distance_au",
                  "not used"},
        Malformed{"irradiance not covering the wavelengths",
                  [](json& j) { j["sun"]["irradiance"] = {{"500", 1.0}, {"600", 1.0}}; }, "/sun/irradiance",
                  "must cover every working wavelength"},
        Malformed{"irradiance keyword", [](json& j) { j["sun"]["irradiance"] = "planck"; }, "/sun/irradiance",
                  "\"kurucz\""},
        Malformed{"latitude out of range", [](json& j) { j["camera"]["surface"]["latitude_deg"] = 95; },
                  "/camera/surface/latitude_deg", "[-90, 90] deg"},
        Malformed{"altitude below 0.1 m", [](json& j) { j["camera"]["surface"]["altitude_m"] = 0; },
                  "/camera/surface/altitude_m", "must be in [0.1"},
        Malformed{"two camera positions", [](json& j) { j["camera"]["position_m"] = {1e8, 0, 0}; }, "/camera",
                  "exactly one of \"position_m\", \"surface\""},
        Malformed{"up with look", [](json& j) { j["camera"]["up"] = {0, 0, 1}; }, "/camera/up", "roll_deg"},
        Malformed{"up parallel to forward",
                  [](json& j) {
                    j["camera"] = {{"position_m", {2e7, 0, 0}}, {"forward", {-1, 0, 0}}, {"up", {2, 0, 0}}};
                  },
                  "/camera/up", "parallel"},
        Malformed{"look_at the camera itself",
                  [](json& j) { j["camera"] = {{"position_m", {2e7, 0, 0}}, {"look_at", {2e7, 0, 0}}}; },
                  "/camera/look_at", "must differ"},
        Malformed{"both orientation forms",
                  [](json& j) {
                    j["bodies"][0]["orientation"] = {{"axis", {0, 0, 1}}, {"angle_deg", 3}, {"north_pole", {0, 0, 1}}};
                  },
                  "/bodies/0/orientation", "not both"},
        Malformed{"prime meridian along the pole",
                  [](json& j) {
                    j["bodies"][0]["orientation"] = {{"north_pole", {0, 0, 1}}, {"prime_meridian", {0, 0, -3}}};
                  },
                  "/bodies/0/orientation/prime_meridian", "parallel"},
        Malformed{"nine atmospheres",
                  [](json& j) {
                    j["bodies"] = nine_planets_with_atmospheres();
                    j["camera"]["surface"]["body"] = "A";
                  },
                  "/bodies", "at most 8"},
        Malformed{"body not an object", [](json& j) { j["bodies"][1] = 3; }, "/bodies/1", "must be a JSON object"},
        Malformed{"image albedo with a seed", [](json& j) { j["bodies"][1]["albedo"] = {{"image", "x.png"}, {"seed", 1}}; },
                  "/bodies/1/albedo/seed", "unknown key"}));

}  // namespace
}  // namespace zenith::scene
