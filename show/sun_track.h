#pragma once
// The sun's keyframes over show time (docs/shows.md, "Sun track").
//
// Direction: along great circles. Between keys i and i+1 the direction is the
// slerp of their unit vectors; how far along is set by the total angle
// travelled since the first key, A(t), interpolated through the keys' A_i by a
// monotone cubic (Fritsch–Carlson). So the sun never backtracks between two
// keys, moves at a continuous angular speed through keys (where the track
// bends only in direction), and sits exactly on every key at its time.
// Angular radius and each wavelength's irradiance: monotone cubics too, so
// they stay between their keys (and ≥ 0).
#include <vector>

#include <glm/vec3.hpp>

#include "scene/scene.h"
#include "show/monotone_cubic.h"

namespace zenith::show {

/// Consecutive sun keys must be less than this far apart (antipodal
/// directions have no unique great circle).
inline constexpr double kMaxSunKeyAngle_deg = 179.0;

struct SunKey {
  double t_s = 0.0;
  scene::Sun sun;
};

class SunTrack {
 public:
  /// Keys strictly increasing in t_s, at least one, all with as many
  /// irradiance values. Throws std::invalid_argument otherwise.
  explicit SunTrack(const std::vector<SunKey>& keys);

  scene::Sun at(double t_s) const;
  const std::vector<double>& key_times_s() const { return times_s_; }

 private:
  std::vector<double> times_s_;
  std::vector<glm::dvec3> directions_;
  std::vector<double> travelled_at_key_rad_;
  MonotoneCubic travelled_rad_;
  MonotoneCubic angular_radius_rad_;
  std::vector<MonotoneCubic> irradiance_W_m2_nm_;  ///< one per wavelength
};

/// The angle between two unit vectors, accurate near 0 and π (atan2 of |a × b| and a · b).
double angle_between_rad(const glm::dvec3& a, const glm::dvec3& b);

}  // namespace zenith::show
