#pragma once
// The camera's keyframes over show time (docs/shows.md, "Camera track").
//
// Position, two schemes:
//  * every key stands on the same body ("surface"): the path follows the
//    ground. The keys' directions from the body's centre (unit vectors in the
//    body frame) are joined by a centripetal Catmull–Rom spline and projected
//    back onto the unit sphere — no seam at ±180° longitude, no pinch at the
//    poles — and the altitude is a monotone cubic (Fritsch–Carlson) in
//    log(altitude), so it never leaves the range of the two keys around it: a
//    descent from 400 km to 2 m stays above 2 m, and eases in at a constant
//    rate of descent in log altitude (slowing in metres per second toward
//    the ground);
//  * otherwise: a centripetal Catmull–Rom spline through the keys' world
//    positions (the show loader checks it stays clear of every body).
// Show time maps onto the spline's knots through a monotone cubic through
// (t_i, knot_i) (Fritsch–Carlson), so the camera's velocity is continuous in
// show time across keys, not only in the spline's own parameter (a linear
// map per segment would jump in speed wherever neighbouring segments have
// different knot-per-second ratios).
// Orientation: squad through the keys' orientations (squad.h).
#include <cstddef>
#include <optional>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "scene/scene.h"
#include "scene/scene_loader.h"
#include "show/catmull_rom.h"
#include "show/monotone_cubic.h"
#include "show/squad.h"

namespace zenith::show {

/// Consecutive surface keys must be less than this far apart, seen from the
/// body's centre (the spline of their directions must not pass near the centre).
inline constexpr double kMaxSurfaceKeyAngle_deg = 120.0;

struct CameraKey {
  double t_s = 0.0;
  scene::CameraPlacement placement;
};

class CameraTrack {
 public:
  /// Keys strictly increasing in t_s, at least one; `bodies` those of the
  /// scene the placements were read in.
  CameraTrack(const std::vector<CameraKey>& keys, const std::vector<scene::Body>& bodies);

  glm::dvec3 position_m(double t_s) const;
  glm::dquat orientation(double t_s) const;
  /// The body every key stands on, when the path follows its surface.
  const std::optional<std::size_t>& surface_body() const { return surface_body_; }
  /// Surface paths: the altitude above that body at t.
  double altitude_m(double t_s) const;
  const std::vector<double>& key_times_s() const { return times_s_; }

 private:
  std::vector<double> times_s_;
  std::optional<std::size_t> surface_body_;
  glm::dvec3 body_centre_m_{0.0};
  glm::dquat body_orientation_{1, 0, 0, 0};
  double body_radius_m_ = 0.0;
  /// World positions, or (surface paths) body-frame unit directions.
  CentripetalCatmullRom path_;
  MonotoneCubic knot_at_time_;                 ///< show time → the spline's knot
  std::optional<MonotoneCubic> log_altitude_;  ///< surface paths: ln(altitude / 1 m)
  SquadCurve orientation_;
};

}  // namespace zenith::show
