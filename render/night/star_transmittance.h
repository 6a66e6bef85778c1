#pragma once
// A star's light through the atmospheres it crosses (docs/night-sky.md,
// "Rendering the night sky"; step 3 of render/night/star_placement.h): the
// transmittance from the camera to infinity along a ray, read from each
// atmosphere's transmittance table — the one the sky is drawn with, so
// Mars's dust dims stars as it dims the Sun. No GL.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "atmosphere/lut/lookup_tables.h"

namespace zenith::render {

/// An atmosphere a star's light can cross: its planet and its transmittance table.
struct StarAtmosphere {
  glm::dvec3 centre_m{0.0};  ///< world frame
  double ground_radius_m = 0.0, top_radius_m = 0.0;
  const atmosphere::lut::LookupTables* transmittance = nullptr;  ///< geometry, sizes, channels, transmittance filled
};

/// The transmittance along a ray from `camera_m` in unit direction `d` to
/// infinity through `a` (1 where it misses the shell, 0 where it meets the
/// ground) into `out` (channels values).
void star_transmittance(const StarAtmosphere& a, const glm::dvec3& camera_m, const glm::dvec3& d, double* out);

/// star_transmittance from one camera, for every direction of a frame: every
/// ray is read at one radius — the camera's, or the top's where the camera is
/// outside the shell and the ray enters it — so the bilinear filter's weight
/// between the table's two rows there is the same for all, and the rows are
/// blended once, per channel, into one row. A star then costs its distance to
/// the top (the row's coordinate u_μ, as transmittance_uv), the row's two taps
/// and one lerp per channel, where star_transmittance recomputes the row
/// weight's square roots and reads four texels. The same bilinear filter with
/// its sum reordered: the same figures to a few ulps (values ≤ 1; asserted
/// within 1e-15 of star_transmittance by
/// StarField.TheCameraTransmittanceIsTheTablesReadWithinRounding), so neither
/// the pass's stars nor star_visibility's bounds move.
class CameraTransmittance {
 public:
  CameraTransmittance(const StarAtmosphere& atmosphere, const glm::dvec3& camera_m);
  /// star_transmittance(atmosphere, camera_m, d, out).
  void operator()(const glm::dvec3& d, double* out) const;

 private:
  atmosphere::lut::ShellGeometry geometry_;  // the table's
  glm::dvec3 p_;                             // the camera from the planet's centre
  double ground_ = 0.0, top_ = 0.0;          // StarAtmosphere's radii
  double r_ = 0.0, r_at_ = 0.0, d_min_ = 0.0, d_max_ = 0.0;
  std::size_t width_ = 0, channels_ = 0;
  std::vector<double> row_;  // [texel][channel]
};

}  // namespace zenith::render
