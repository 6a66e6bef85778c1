#include "cluster/operator/sun_override.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "core/units.h"
#include "scene/scene_loader.h"

namespace zenith::cluster {

SunOverride::SunOverride(const scene::Scene& scene)
    : bodies_(scene.bodies), scene_camera_m_(scene.camera.position_m), scene_sun_direction_(scene.sun.direction) {}

scene::LocalHorizon SunOverride::horizon_at(const glm::dvec3& camera_m) const {
  if (bodies_.empty()) return scene::LocalHorizon{};  // world +z up, +y north: scenes always have a body
  return scene::local_horizon_at(camera_m, bodies_[scene::nearest_body(bodies_, camera_m)]);
}

scene::SkyAngles SunOverride::angles_of(const FrameState& state) const {
  return horizon_at(state.camera_position_m).angles_of(state.sun_direction);
}

scene::SkyAngles SunOverride::set(const operator_command::Sun& sun, const FrameState* latest) {
  scene::SkyAngles now = angles_             ? *angles_
                         : latest != nullptr ? angles_of(*latest)
                                             : horizon_at(scene_camera_m_).angles_of(scene_sun_direction_);
  if (sun.elevation_deg) now.elevation_deg = *sun.elevation_deg;
  if (sun.azimuth_deg) now.azimuth_deg = *sun.azimuth_deg;
  now.azimuth_deg = std::fmod(now.azimuth_deg, 360.0);
  if (now.azimuth_deg < 0.0) now.azimuth_deg += 360.0;
  if (now.azimuth_deg >= 360.0) now.azimuth_deg = 0.0;
  angles_ = now;
  return now;
}

void SunOverride::apply(FrameState& state) const {
  if (!angles_) return;
  state.sun_direction =
      glm::normalize(horizon_at(state.camera_position_m)
                         .direction(angles_->azimuth_deg * core::kDeg, angles_->elevation_deg * core::kDeg));
}

}  // namespace zenith::cluster
