#pragma once
// The operator's sun (docs/operator.md, "Sun"): an elevation and an azimuth in
// the local horizon of the camera (docs/scenes.md, "Frames and conventions")
// that replace the direction of the show's sun track, or of the default
// show's turning sun, from the next frame on until cleared. The horizon is
// the camera's of each frame, on the body nearest to it, so a moving camera
// keeps the sun where the operator put it in its sky. The sun's angular
// radius and irradiance stay the show's. No sockets, no clock.
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "cluster/operator/operator_command.h"
#include "cluster/protocol/messages.h"
#include "scene/local_horizon.h"
#include "scene/scene.h"

namespace zenith::cluster {

/// Invariant: when set, the angles are in range (elevation [−90, 90],
/// azimuth [0, 360)).
class SunOverride {
 public:
  /// The bodies whose local horizons the angles refer to (the scene's; at
  /// least one), and the scene's camera and sun for a command before the
  /// first frame.
  explicit SunOverride(const scene::Scene& scene);

  /// The sun's azimuth and elevation in the local horizon of `state`'s camera.
  scene::SkyAngles angles_of(const FrameState& state) const;
  /// An operator's `sun`: the angle it leaves out keeps its present value —
  /// the override's, else that of the sun of `latest` (the latest frame
  /// started; nullptr before the first: the scene's sun). Returns the angles
  /// set (the azimuth wrapped into [0, 360)).
  scene::SkyAngles set(const operator_command::Sun& sun, const FrameState* latest);
  /// The show's (or scene's) sun again from the next frame.
  void clear() { angles_.reset(); }
  /// The operator's angles, nullopt when the show's sun applies.
  const std::optional<scene::SkyAngles>& angles() const { return angles_; }

  /// With an override: `state`'s sun direction becomes the operator's angles
  /// in the local horizon of its camera. Without one, nothing changes.
  void apply(FrameState& state) const;

 private:
  /// The local horizon of a camera at `camera_m`, on the body nearest to it.
  scene::LocalHorizon horizon_at(const glm::dvec3& camera_m) const;

  std::vector<scene::Body> bodies_;
  glm::dvec3 scene_camera_m_{0.0};
  glm::dvec3 scene_sun_direction_{0, 0, 1};
  std::optional<scene::SkyAngles> angles_;
};

}  // namespace zenith::cluster
