#pragma once
// The angular (azimuthal equidistant) fisheye: the planetarium "dome master".
// The angle of a ray from the optical axis is proportional to the distance of its
// pixel from the centre of the image circle:
//
//   θ = r · (fov / 2) / radius_px          r = |pixel − centre| in pixels
//
// and the ray's azimuth about the axis is the pixel's azimuth about the centre.
// Pixels outside the circle (r > radius_px, i.e. θ > fov / 2) have no ray.
//
// Dome-master orientation (tilt 0, rotation 0), as seen from inside the dome
// looking up at the zenith with the front of the dome at the bottom of the image
// (docs/projections.md has the diagram):
//
//   circle centre          → +y (up, the dome's zenith: the optical axis)
//   bottom-centre of rim   → −z (forward; the horizon in front for fov 180)
//   right of rim           → +x (right)
//   top-centre of rim      → +z (backward)
//   left of rim            → −x (left)
//
// i.e. the camera looks up with its image-right +x and its image-up +z: a
// rotation, not a mirror image, of a camera looking forward.
//
// tilt_deg turns the optical axis from up toward forward about +x (a dome tilted
// 30° toward its front has tilt 30; tilt 90 is a forward-looking fisheye with
// the sky at the top). rotation_deg spins the picture about the image-circle
// centre: positive turns it counter-clockwise on screen (forward moves from the
// bottom toward the right for rotation 90).
//
// With the optical-frame basis in camera coordinates
//   e_right = image right, e_up = image up, e_axis = optical axis,
// and (dx, dy) = (x − centre_x, centre_y − y) (image y points down, dy up):
//
//   ray = sin θ · (dx · e_right + dy · e_up) / r + cos θ · e_axis
//
// For fov 360 the whole sphere fits in the disc and the rim is the direction
// opposite the optical axis (the nadir at tilt 0).
#include <optional>

#include <glm/mat3x3.hpp>

#include "core/units.h"
#include "warp/projection.h"

namespace zenith::warp {

/// The parameters of a FisheyeProjection.
struct FisheyeParameters {
  double fov_deg = 180.0;  ///< full field of view across the image circle, in [1, 360] degrees
  /// Axis turned from up (+y) toward forward (−z), in [−90, 90] degrees; also
  /// read as the same tilt ± 360° ([270, 360] for [−90, 0]) and kept wrapped.
  double tilt_deg = 0.0;
  /// Centre of the image circle in continuous pixel coordinates, in [−1e6, 1e6] px;
  /// unset: the image centre (width / 2, height / 2).
  std::optional<double> centre_x_px = std::nullopt;
  std::optional<double> centre_y_px = std::nullopt;
  /// Radius of the image circle (the circle at fov / 2 from the axis), in (0, 1e6]
  /// px; unset: min(width, height) / 2. A larger radius than the image crops the
  /// circle (a "truncated" dome master); a smaller one leaves a black border.
  std::optional<double> radius_px = std::nullopt;
  double rotation_deg = 0.0;  ///< picture spun counter-clockwise on screen about the centre, in [−360, 360] degrees
};

/// What gpu(), describe() and max_pixel_angle_rad() return, computed once when
/// the projection is built (ClosedFormProjection):
///  * gpu(): kind fisheye:
///      params[0] = (centre_x_px, centre_y_px, radians per pixel = (fov/2) / radius_px, fov/2 in radians)
///      params[1] = (e_right.x, e_right.y, e_right.z, 0)
///      params[2] = (e_up.x,    e_up.y,    e_up.z,    0)
///      params[3] = (e_axis.x,  e_axis.y,  e_axis.z,  0)
///    in the camera frame (the columns of optical_frame()).
///  * describe(): "fisheye 180° 1024×1024", with ", tilt 30°", ", rotation 90°" and
///    ", circle r=600 px at (512, 512)" appended where not the defaults.
///  * max_pixel_angle_rad(): sqrt(2) · (fov / 2) / radius_px: the map moves a ray by at most
///    (fov / 2) / radius_px radians per pixel in any direction (radially exactly
///    that, tangentially sin θ / r ≤ θ / r), and two points of one pixel lie at
///    most a diagonal (sqrt(2) px) apart along a segment inside the circle.
class FisheyeProjection final : public ClosedFormProjection {
 public:
  /// Throws std::invalid_argument naming the parameter, its value and the
  /// allowed range when a size or a parameter is out of range (or not finite).
  FisheyeProjection(int width_px, int height_px, const FisheyeParameters& parameters = {});

  double fov_deg() const { return fov_deg_; }
  double tilt_deg() const { return tilt_deg_; }
  double rotation_deg() const { return rotation_deg_; }
  double centre_x_px() const { return centre_x_px_; }
  double centre_y_px() const { return centre_y_px_; }
  double radius_px() const { return radius_px_; }
  /// Optical frame → camera frame: columns e_right, e_up, e_axis (tilt and
  /// rotation included).
  const glm::dmat3& optical_frame() const { return frame_; }

  /// Nothing outside the image circle (r > radius_px) and for non-finite input.
  std::optional<glm::dvec3> ray(double x_px, double y_px) const override;
  /// Nothing when the direction is more than fov / 2 from the axis, and for the
  /// zero vector or non-finite input. The direction opposite the axis (fov 360
  /// only) maps to the rim point below the centre on screen.
  std::optional<glm::dvec2> pixel(const glm::dvec3& direction) const override;

  /// The equidistant map's Jacobian (a = rad_per_px radians per pixel, θ = a r
  /// from the axis): Ω = a² sin θ / θ, within kClosedFormSolidAngleLimit_rad of
  /// the axis and a pixel inside the rim; elsewhere (near θ = 180°, where
  /// sin θ / θ vanishes, and at the rim) the rays' quotient. It differs from
  /// Ω_rays by the latter's truncation, |Ω/Ω_rays − 1| ≤ a²/6 (from its Taylor
  /// series: a²/12 at the axis, 0.143 a² at 150°; 9.4e-6 / 6 on a 1024² 180°
  /// master).
  double pixel_solid_angle_sr(double x_px, double y_px) const override;
  double solid_angle_relative_bound() const override { return rad_per_px_ * rad_per_px_ / 6.0; }
  static constexpr double kClosedFormSolidAngleLimit_rad = 150.0 * core::kDeg;

 private:
  double fov_deg_, tilt_deg_, rotation_deg_;
  double centre_x_px_, centre_y_px_, radius_px_;
  double half_fov_rad_;
  double rad_per_px_;  // (fov / 2) / radius_px
  glm::dmat3 frame_;
};

}  // namespace zenith::warp
