#pragma once
// A cylindrical panorama: a curved screen, a display wall wrapped around the
// audience, a 360° strip. docs/projections.md has the diagrams.
//
// The cylinder has its own frame, oriented like a PlanarFrustum's: its forward
// is the frame's −z, its axis (the cylinder's) the frame's +y. The horizontal
// angle (azimuth φ about +y, positive toward +x) is linear in x over the
// horizontal field of view, centred on forward; the vertical is a central
// projection onto the cylinder of radius 1 (perspective along every vertical
// line of the image), linear in tangent space between the bottom and top angles:
//
//   φ(x) = (x / width − 1/2) · horizontal_fov                   x ∈ [0, width]
//   v(y) = tan(up) + y / height · (tan(down) − tan(up))          y ∈ [0, height]
//   ray_cylinder(x, y) = normalize(sin φ, v, −cos φ)
//
// so the image's left edge looks horizontal_fov / 2 to the left of forward, the
// top edge `up_deg` above the horizon of the cylinder frame. The frame is then
// oriented in the camera frame by yaw, pitch and roll exactly as a PlanarFrustum
// (warp/planar_projection.h): ray_camera = R_yaw · R_pitch · R_roll · ray_cylinder.
//
// ray() is defined for every finite y and for |φ| ≤ π (one turn about the axis,
// centred on forward); pixel() is its inverse there. For a 360° cylinder the
// columns x = 0 and x = width see the same directions; pixel() returns x in
// [0, width) then, so every direction except the cylinder's two poles has a
// pixel in [0, width) (its y may lie outside the image).
#include <glm/mat3x3.hpp>

#include "warp/projection.h"

namespace zenith::warp {

/// The parameters of a CylindricalProjection, angles in degrees.
struct CylindricalParameters {
  double horizontal_fov_deg = 360.0;  ///< the image's width as an angle about the axis, in (0, 360]
  double down_deg = -45.0;  ///< angle of the bottom edge (y = height) from the horizon, in (−89, 89), < up_deg
  double up_deg = 45.0;     ///< angle of the top edge (y = 0) from the horizon, in (−89, 89)
  // Yaw, pitch and roll: each read in [−360, 360] and kept normalized (yaw,
  // roll in (−180, 180], pitch in [−90, 90]; warp/orientation_angles.h).
  double yaw_deg = 0.0;    ///< positive turns forward right (toward +x), as PlanarFrustum
  double pitch_deg = 0.0;  ///< positive tips forward up (toward +y), as PlanarFrustum
  double roll_deg = 0.0;   ///< positive banks right, as PlanarFrustum
};

/// What gpu(), describe() and max_pixel_angle_rad() return, computed once when
/// the projection is built (ClosedFormProjection):
///  * gpu(): kind cylindrical, about the image centre (x_c, y_c) = (width / 2, height / 2):
///      φ = (x − x_c) · k_φ,   v = v_c + (y − y_c) · k_v,
///      ray = normalize(sin φ · e_right + v · e_axis − cos φ · e_back),  no ray where |x − x_c| > h
///      params[0] = (x_c, k_φ = horizontal_fov / width (rad/px), y_c, k_v = (tan(down) − tan(up)) / height)
///      params[1] = (e_right.x, e_right.y, e_right.z, v_c = (tan(up) + tan(down)) / 2)
///      params[2] = (e_axis.x,  e_axis.y,  e_axis.z,  h = π / k_φ = width / 2 · 360° / horizontal_fov (px))
///      params[3] = (e_back.x,  e_back.y,  e_back.z,  0)
///    with e_right, e_axis, e_back the columns of rotation().
///  * describe(): "cylindrical 360°×90° (down -45° up 45°) 4096×1024", with
///    ", yaw 10° pitch 0° roll 0°" appended when the cylinder is turned.
///  * max_pixel_angle_rad(): sqrt(k_φ² / (1 + ρ²) + k_v² / (1 + ρ²)²), ρ the smallest |v| over the image
///    (0 when the horizon is in it): the ray's elevation α = atan v and azimuth φ
///    have the metric dα² + cos²α dφ² = dv² / (1 + v²)² + dφ² / (1 + v²), and two
///    points of one pixel differ by at most one pixel in x and in y.
class CylindricalProjection final : public ClosedFormProjection {
 public:
  /// Throws std::invalid_argument naming the parameter, its value and the
  /// allowed range when a size or a parameter is out of range (or not finite),
  /// or when down_deg >= up_deg.
  CylindricalProjection(int width_px, int height_px, const CylindricalParameters& parameters);

  const CylindricalParameters& parameters() const { return parameters_; }
  /// Cylinder frame → camera frame (R_yaw · R_pitch · R_roll, PlanarProjection's
  /// rotation()): column 0 is φ = 90° (right), column 1 the cylinder's axis,
  /// column 2 backward (forward is −column 2).
  const glm::dmat3& rotation() const { return rotation_; }

  /// Nothing for |φ(x)| > π (beyond one turn about the axis) and non-finite input.
  std::optional<glm::dvec3> ray(double x_px, double y_px) const override;
  /// Nothing for directions along the cylinder's axis (its poles), the zero
  /// vector and non-finite input. x from the azimuth in [−π, π]; a 360°
  /// cylinder returns x in [0, width) (the seam direction, φ = ±π, at x = 0).
  std::optional<glm::dvec2> pixel(const glm::dvec3& direction) const override;

 private:
  CylindricalParameters parameters_;
  double tan_down_, tan_up_;
  double rad_per_px_;    // k_φ > 0
  double tan_per_px_y_;  // k_v < 0
  double half_turn_px_;  // π / k_φ, as width / 2 · 360° / fov: the largest |x − width / 2| with a ray
  glm::dmat3 rotation_;
};

}  // namespace zenith::warp
