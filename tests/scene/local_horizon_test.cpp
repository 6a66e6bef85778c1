// The local horizon frame (scene/local_horizon.h; docs/scenes.md, "Frames and
// conventions"): directions from azimuth and elevation and back, the pole,
// and agreement with what the scene loader makes of a sun in the sky.
#include "scene/local_horizon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>

#include "core/units.h"
#include "scene/scene_loader.h"

namespace zenith::scene {
namespace {

using core::kDeg;
using glm::dvec3;

Body body_at_origin() {
  Body b;
  b.radius_m = 6.4e6;
  return b;
}

TEST(LocalHorizon, AnglesOfADirectionAreTheAnglesThatMadeIt) {
  const Body body = body_at_origin();
  // 45° N, 30° E of the prime meridian, 2 m up.
  const dvec3 point = (body.radius_m + 2.0) * dvec3(std::cos(45 * kDeg) * std::cos(30 * kDeg),
                                                    std::cos(45 * kDeg) * std::sin(30 * kDeg), std::sin(45 * kDeg));
  const LocalHorizon h = local_horizon_at(point, body);
  EXPECT_NEAR(glm::dot(h.up, h.north), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(glm::cross(h.north, h.up) - h.east), 0.0, 1e-12);
  EXPECT_GT(glm::dot(h.north, dvec3(0, 0, 1)), 0.0) << "north points toward the pole";
  for (const double azimuth : {0.0, 45.0, 90.0, 180.0, 271.5, 359.0})
    for (const double elevation : {-89.0, -19.8, 0.0, 1.0, 60.0, 89.5}) {
      const SkyAngles a = h.angles_of(h.direction(azimuth * kDeg, elevation * kDeg));
      EXPECT_NEAR(a.azimuth_deg, azimuth, 1e-9) << azimuth << " " << elevation;
      EXPECT_NEAR(a.elevation_deg, elevation, 1e-9) << azimuth << " " << elevation;
    }
  EXPECT_NEAR(glm::length(h.direction(90 * kDeg, 0.0) - h.east), 0.0, 1e-12) << "azimuth 90° is east";
  const SkyAngles west = h.angles_of(-3.0 * h.east);
  EXPECT_NEAR(west.azimuth_deg, 270.0, 1e-12) << "any length";
  const SkyAngles zenith = h.angles_of(h.up);
  EXPECT_EQ(zenith.azimuth_deg, 0.0);
  EXPECT_NEAR(zenith.elevation_deg, 90.0, 1e-12);
}

TEST(LocalHorizon, AtThePoleNorthIsAlongThePrimeMeridian) {
  const Body body = body_at_origin();
  const LocalHorizon h = local_horizon_at(dvec3(0, 0, body.radius_m + 1.0), body);
  EXPECT_NEAR(glm::length(h.north - dvec3(-1, 0, 0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(h.up - dvec3(0, 0, 1)), 0.0, 1e-12);
}

TEST(LocalHorizon, ReadsBackTheSkyOfASceneFile) {
  const Scene scene = load_scene(std::filesystem::path(ZENITH_SOURCE_DIR) / "configs/scenes/earth-sunset.json");
  const LocalHorizon h = local_horizon_at(scene.camera.position_m, scene.bodies[0]);
  const SkyAngles sun = h.angles_of(scene.sun.direction);  // "sky": elevation 1°, azimuth 272°
  EXPECT_NEAR(sun.elevation_deg, 1.0, 1e-9);
  EXPECT_NEAR(sun.azimuth_deg, 272.0, 1e-9);
}

}  // namespace
}  // namespace zenith::scene
