#pragma once
// A pinhole camera with an asymmetric ("off-axis") frustum: a flat projector
// channel, a display wall, a CAVE side, one slice of a cluster. docs/projections.md
// has the diagrams.
//
// The frustum has its own frame: its axis is the frame's −z, its up the frame's
// +y. The image plane z = −1 of that frame is mapped linearly in tangent space:
//
//   u(x) = tan(left) + x / width  · (tan(right) − tan(left))     x ∈ [0, width]
//   v(y) = tan(up)   + y / height · (tan(down) − tan(up))        y ∈ [0, height]
//   ray_frustum(x, y) = normalize(u, v, −1)
//
// so the left edge of the image (x = 0) looks `left_deg` to the side of the axis,
// the top edge (y = 0) `up_deg` above it. The frustum frame is then oriented in
// the camera frame by yaw, pitch and roll (degrees, aircraft convention):
//
//   ray_camera = R_yaw · R_pitch · R_roll · ray_frustum
//
//  * roll  φ: a right-handed turn about the view direction (−z): the frustum's
//             up tilts toward +x (banks right); the picture turns counter-clockwise;
//  * pitch θ: about +x, positive looks up: the axis becomes (0, sin θ, −cos θ);
//  * yaw   ψ: about +y, positive turns right (clockwise seen from above, like a
//             compass heading): the axis becomes (sin ψ cos θ, sin θ, −cos ψ cos θ).
#include <glm/mat3x3.hpp>

#include "warp/projection.h"

namespace zenith::warp {

/// The frustum of a PlanarProjection, angles in degrees. The four edge angles are
/// signed angles from the frustum's axis, measured in tangent space: left/down
/// are negative when the axis lies inside the frustum (a symmetric 60° × 40°
/// frustum is {-30, 30, -20, 20}); a frustum entirely to the right of its axis
/// has 0 < left < right.
struct PlanarFrustum {
  double left_deg;   ///< angle of the image's left edge (x = 0), in (−89, 89), < right_deg
  double right_deg;  ///< angle of the image's right edge (x = width), in (−89, 89)
  double down_deg;   ///< angle of the image's bottom edge (y = height), in (−89, 89), < up_deg
  double up_deg;     ///< angle of the image's top edge (y = 0), in (−89, 89)
  /// Yaw, pitch and roll: each read in [−360, 360] (tools write [0, 360) as
  /// often as (−180, 180]); PlanarProjection keeps the same rotation with yaw
  /// and roll in (−180, 180] and pitch in [−90, 90] (warp/orientation_angles.h).
  double yaw_deg = 0.0;    ///< positive turns the axis right (toward +x)
  double pitch_deg = 0.0;  ///< positive turns the axis up (toward +y)
  double roll_deg = 0.0;   ///< positive banks right (the frustum's up tilts toward +x)
};

/// What gpu(), describe() and max_pixel_angle_rad() return, computed once when
/// the projection is built (ClosedFormProjection):
///  * gpu(): kind planar; the unnormalized ray is affine in the pixel position. Taken
///    about the image centre (x_c, y_c) = (width / 2, height / 2), where float
///    loses least (x − x_c is exact, and the terms stay small near the centre):
///      d(x, y) = (x − x_c) · A + (y − y_c) · B + C,   ray = normalize(d),
///    with A = ∂d/∂x, B = ∂d/∂y and C = d(x_c, y_c) in the camera frame (R = rotation()):
///      params[0] = (A.x, A.y, A.z, x_c)   A = R · ((tan(right) − tan(left)) / width, 0, 0)
///      params[1] = (B.x, B.y, B.z, y_c)   B = R · (0, (tan(down) − tan(up)) / height, 0)
///      params[2] = (C.x, C.y, C.z, 0)     C = R · ((tan(left) + tan(right)) / 2, (tan(up) + tan(down)) / 2, −1)
///      params[3] = (0, 0, 0, 0)
///    Float keeps the ray within about 1e-7 · (1 + the frustum's largest |tan|) radians.
///  * describe(): "planar 60°×40° (left -30° right 30° down -20° up 20°) 1920×1080", with
///    ", yaw 10° pitch 0° roll 0°" appended when the frustum is rotated.
///  * max_pixel_angle_rad(): (pixel diagonal in tangent units) / sqrt(1 + ρ²), ρ the smallest distance
///    of the image rectangle from the axis in tangent units: the gnomonic map
///    moves the ray by at most 1 / sqrt(1 + ρ²) radians per tangent unit.
class PlanarProjection final : public ClosedFormProjection {
 public:
  /// Throws std::invalid_argument naming the parameter, its value and the allowed
  /// range when a size or a frustum angle is out of range (yaw, pitch, roll
  /// outside [−360, 360]), or when left_deg >= right_deg or down_deg >= up_deg.
  PlanarProjection(int width_px, int height_px, const PlanarFrustum& frustum);

  /// A symmetric frustum looking along −z with square pixels: the horizontal
  /// field of view `horizontal_fov_deg`, in (0, 178), and the vertical one from
  /// the aspect ratio: tan(vertical / 2) = tan(horizontal / 2) · height / width.
  /// Throws std::invalid_argument when either field of view is not below 178°
  /// (each half-angle must be below the frustum's 89°).
  static PlanarProjection symmetric(int width_px, int height_px, double horizontal_fov_deg);

  /// The frustum, yaw, pitch and roll normalized (the same rotation as given).
  const PlanarFrustum& frustum() const { return frustum_; }
  /// Frustum frame → camera frame (R_yaw · R_pitch · R_roll); column 2 is the
  /// frustum's +z, so the frustum's axis is −rotation()[2].
  const glm::dmat3& rotation() const { return rotation_; }

  /// Defined for every finite position: positions outside the image rectangle
  /// extend the image plane (nothing only for non-finite input).
  std::optional<glm::dvec3> ray(double x_px, double y_px) const override;
  /// Nothing for directions at or beyond 90° from the frustum's axis (they do
  /// not cross its image plane), for the zero vector and for non-finite input.
  std::optional<glm::dvec2> pixel(const glm::dvec3& direction) const override;

  /// The pinhole's Jacobian at the image-plane point (u, v) of the pixel, with
  /// t_x, t_y its tangent steps per pixel: Ω = |t_x t_y| / (1 + u² + v²)^(3/2),
  /// everywhere. |Ω/Ω_rays − 1| ≤ max(t_x, t_y)²/4, attained on the axis where
  /// the rays' chords are t/√(1 + t²/4) (the bound carries 1e-3 of itself and
  /// 1e-12 for rounding).
  double pixel_solid_angle_sr(double x_px, double y_px) const override;
  double solid_angle_relative_bound() const override;

 private:
  PlanarFrustum frustum_;
  double tan_left_, tan_right_, tan_down_, tan_up_;
  double tan_per_px_x_, tan_per_px_y_;  // du/dx > 0, dv/dy < 0
  glm::dmat3 rotation_;
};

}  // namespace zenith::warp
