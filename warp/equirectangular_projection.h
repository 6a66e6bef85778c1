#pragma once
// The equirectangular (longitude/latitude, plate carrée) panorama: the whole
// sphere in a 2:1 image, or a rectangle of longitudes and latitudes of it.
// docs/projections.md has the diagram.
//
// Longitude λ and latitude β are measured in the camera frame: λ = 0, β = 0 is
// forward (−z), β = +90° is up (+y), λ = +90° is right (+x), λ = ±180° backward
// (+z). Both are linear in the pixel position, longitude increasing to the
// right and latitude upward (image y points down):
//
//   λ(x) = longitude_min + x / width  · (longitude_max − longitude_min)   x ∈ [0, width]
//   β(y) = latitude_max  − y / height · (latitude_max − latitude_min)     y ∈ [0, height]
//   ray  = (cos β · sin λ, sin β, −cos β · cos λ)
//
// The defaults (λ ∈ [−180°, 180°], β ∈ [−90°, 90°]) put forward at the image
// centre, backward on the left and right edges (the seam), up along the top row
// and down along the bottom row.
//
// ray() is defined for |λ − λ_c| ≤ 180° (one turn about +y, centred on the
// range's middle longitude λ_c) and |β| ≤ 90°; pixel() is its inverse there.
// For a 360° range the columns x = 0 and x = width see the same directions;
// pixel() returns x in [0, width) then.
#include "warp/projection.h"

namespace zenith::warp {

/// The longitude and latitude range of an EquirectangularProjection, degrees.
struct EquirectangularParameters {
  /// Longitude of the image's left edge (x = 0), in [−360, 360], < longitude_max_deg.
  double longitude_min_deg = -180.0;
  /// Longitude of the image's right edge (x = width), in [−360, 360]; the range
  /// longitude_max_deg − longitude_min_deg is at most 360.
  double longitude_max_deg = 180.0;
  double latitude_min_deg = -90.0;  ///< latitude of the bottom edge (y = height), in [−90, 90], < latitude_max_deg
  double latitude_max_deg = 90.0;   ///< latitude of the top edge (y = 0), in [−90, 90]
};

/// What gpu(), describe() and max_pixel_angle_rad() return, computed once when
/// the projection is built (ClosedFormProjection):
///  * gpu(): kind equirectangular, about the image centre (x_c, y_c) = (width / 2, height / 2):
///      λ' = (x − x_c) · k_λ  (λ − λ_c),   β = β_c + (y − y_c) · k_β,
///      no ray where |x − x_c| > h or |β| > π/2, else with λ = λ_c + λ':
///      ray = (cos β · sin λ, sin β, −cos β · cos λ)
///      params[0] = (x_c, k_λ = (longitude_max − longitude_min) / width (rad/px),
///                   y_c, k_β = −(latitude_max − latitude_min) / height (rad/px))
///      params[1] = (λ_c, β_c (rad), h = π / k_λ (px), π/2)
///      params[2] = params[3] = (0, 0, 0, 0)
///  * describe(): "equirectangular 360°×180° (longitude -180° to 180°, latitude -90° to 90°) 2048×1024".
///  * max_pixel_angle_rad(): sqrt(k_β² + cos²β₀ · k_λ²), β₀ the latitude of the image nearest the
///    equator: the sphere's metric is dβ² + cos²β dλ², and two points of one pixel
///    differ by at most one pixel in x and in y.
class EquirectangularProjection final : public ClosedFormProjection {
 public:
  /// Throws std::invalid_argument naming the parameter, its value and the
  /// allowed range when a size or a parameter is out of range (or not finite),
  /// when a minimum is not below its maximum or the longitudes span over 360°.
  EquirectangularProjection(int width_px, int height_px, const EquirectangularParameters& parameters = {});

  const EquirectangularParameters& parameters() const { return parameters_; }

  /// Nothing for |λ − λ_c| > 180°, |β| > 90° and non-finite input.
  std::optional<glm::dvec3> ray(double x_px, double y_px) const override;
  /// Every direction but the zero vector (and non-finite input) has a pixel:
  /// λ is taken within 180° of λ_c and lands in [0, width) for a 360° range;
  /// β ∈ [−90°, 90°]. Straight up or down (λ undefined) maps to x = width / 2.
  std::optional<glm::dvec2> pixel(const glm::dvec3& direction) const override;

 private:
  EquirectangularParameters parameters_;
  double centre_longitude_rad_, centre_latitude_rad_;
  double rad_per_px_x_;  // k_λ > 0
  double rad_per_px_y_;  // k_β < 0
  double half_turn_px_;  // π / k_λ, as width / 2 · 360° / range: the largest |x − width / 2| with a ray
};

}  // namespace zenith::warp
