// The operator's sun (cluster/operator/sun_override.h; docs/operator.md, "Sun"):
// angles in the camera's sky replace the frame's sun direction, an angle left
// out keeps its value, clear gives the show's sun back.
#include "cluster/operator/sun_override.h"

#include <gtest/gtest.h>

#include <filesystem>

#include <glm/geometric.hpp>

#include "scene/frame_scene.h"
#include "scene/scene_loader.h"

namespace zenith::cluster {
namespace {

namespace oc = operator_command;

scene::Scene earth_sunset() {
  return scene::load_scene(std::filesystem::path(ZENITH_SOURCE_DIR) / "configs/scenes/earth-sunset.json");
}

TEST(SunOverrideTest, ReplacesTheSunDirectionInTheCamerasSkyUntilCleared) {
  const scene::Scene scene = earth_sunset();
  SunOverride sun(scene);
  FrameState frame = scene::default_show_frame(scene, 0, 0.0, {}, 0);
  const FrameState show_frame = frame;
  sun.apply(frame);
  EXPECT_EQ(frame, show_frame) << "no override: the show's sun";
  EXPECT_NEAR(sun.angles_of(frame).elevation_deg, 1.0, 1e-9);

  // Before the first frame: the other angle is the scene's.
  scene::SkyAngles set = sun.set(oc::Sun{-6.0, std::nullopt}, nullptr);
  EXPECT_EQ(set.elevation_deg, -6.0);
  EXPECT_NEAR(set.azimuth_deg, 272.0, 1e-9);
  sun.apply(frame);
  EXPECT_NEAR(sun.angles_of(frame).elevation_deg, -6.0, 1e-9);
  EXPECT_NEAR(sun.angles_of(frame).azimuth_deg, 272.0, 1e-9);
  EXPECT_NEAR(glm::length(frame.sun_direction), 1.0, 1e-12);
  EXPECT_EQ(frame.sun_irradiance_W_m2_nm, show_frame.sun_irradiance_W_m2_nm) << "only the direction changes";
  EXPECT_EQ(frame.sun_angular_radius_rad, show_frame.sun_angular_radius_rad);

  // The azimuth alone keeps the operator's elevation; negative azimuths wrap.
  set = sun.set(oc::Sun{std::nullopt, -90.0}, &show_frame);
  EXPECT_EQ(set.elevation_deg, -6.0);
  EXPECT_EQ(set.azimuth_deg, 270.0);
  FrameState next = scene::default_show_frame(scene, 1, 0.5, {}, 0);  // a turning sun: replaced as well
  sun.apply(next);
  EXPECT_NEAR(sun.angles_of(next).azimuth_deg, 270.0, 1e-9);
  EXPECT_NEAR(sun.angles_of(next).elevation_deg, -6.0, 1e-9);

  sun.clear();
  EXPECT_FALSE(sun.angles());
  FrameState again = show_frame;
  sun.apply(again);
  EXPECT_EQ(again, show_frame);
  // Without an override, an angle left out is the latest frame's.
  set = sun.set(oc::Sun{std::nullopt, 100.0}, &show_frame);
  EXPECT_NEAR(set.elevation_deg, 1.0, 1e-9);
}

TEST(SunOverrideTest, FollowsTheCamerasHorizonAsTheCameraMoves) {
  const scene::Scene scene = earth_sunset();
  SunOverride sun(scene);
  sun.set(oc::Sun{30.0, 180.0}, nullptr);
  FrameState frame = scene::default_show_frame(scene, 0, 0.0, {}, 0);
  frame.camera_position_m = -frame.camera_position_m;  // the other side of the Earth
  sun.apply(frame);
  EXPECT_NEAR(sun.angles_of(frame).elevation_deg, 30.0, 1e-9);
  EXPECT_NEAR(sun.angles_of(frame).azimuth_deg, 180.0, 1e-9);
  const scene::LocalHorizon there = scene::local_horizon_at(frame.camera_position_m, scene.bodies[0]);
  EXPECT_GT(glm::dot(frame.sun_direction, there.up), 0.0) << "above that camera's horizon";
}

}  // namespace
}  // namespace zenith::cluster
