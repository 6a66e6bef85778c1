#include "warp/cylindrical_projection.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "core/units.h"
#include "warp/orientation_angles.h"
#include "warp/planar_projection.h"

namespace zenith::warp {
namespace {

using core::kDeg;
constexpr double kMaxEdgeDeg = 89.0;  // |down|, |up| < 89°: tan stays below 57.3, as PlanarFrustum

/// The shortest text that reads back as `value` ("-30", "89.0000001").
std::string number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("CylindricalProjection: " + what); }

/// Requires value in the interval with the given ends (open or closed); NaN fails.
void check_range(const char* name, double value, double lo, bool open_lo, double hi, bool open_hi) {
  const bool ok = (open_lo ? lo < value : lo <= value) && (open_hi ? value < hi : value <= hi);
  if (!ok)
    fail(std::string(name) + " = " + number(value) + ": must be in " + (open_lo ? "(" : "[") + number(lo) + ", " +
         number(hi) + (open_hi ? ")" : "]") + " degrees");
}

/// CylindricalProjection's gpu() (the layout documented there): `rad_per_px` is
/// k_φ, `tan_per_px_y` k_v, `half_turn_px` h.
GpuProjection cylindrical_gpu(const glm::dmat3& rotation, double tan_down, double tan_up, double rad_per_px,
                              double tan_per_px_y, double half_turn_px, int width_px, int height_px) {
  GpuProjection out;
  out.kind = ProjectionKind::cylindrical;
  out.params = {std::array<float, 4>{static_cast<float>(0.5 * width_px), static_cast<float>(rad_per_px),
                                     static_cast<float>(0.5 * height_px), static_cast<float>(tan_per_px_y)},
                gpu_vec4(rotation[0], 0.5 * (tan_up + tan_down)), gpu_vec4(rotation[1], half_turn_px),
                gpu_vec4(rotation[2], 0.0)};
  return out;
}

/// CylindricalProjection's describe().
std::string cylindrical_description(const CylindricalParameters& p, int width_px, int height_px) {
  std::ostringstream out;  // 6 significant digits: "73.7398°"
  out << "cylindrical " << p.horizontal_fov_deg << "°×" << p.up_deg - p.down_deg << "° (down " << p.down_deg << "° up "
      << p.up_deg << "°) " << width_px << "×" << height_px;
  if (p.yaw_deg != 0.0 || p.pitch_deg != 0.0 || p.roll_deg != 0.0)
    out << ", yaw " << p.yaw_deg << "° pitch " << p.pitch_deg << "° roll " << p.roll_deg << "°";
  return out.str();
}

/// CylindricalProjection's max_pixel_angle_rad().
double cylindrical_max_pixel_angle_rad(double tan_down, double tan_up, double rad_per_px, double tan_per_px_y) {
  // With elevation α = atan v, the sphere's metric dα² + cos²α dφ² reads
  // dv² / (1 + v²)² + dφ² / (1 + v²): both factors are largest where |v| is
  // smallest. A straight segment between two points of one pixel stays in the
  // image rectangle (where |v| ≥ ρ) and moves at most one pixel in x and in y.
  const double nearest_v = std::clamp(0.0, tan_down, tan_up);
  const double stretch = 1.0 + nearest_v * nearest_v;
  return std::sqrt(rad_per_px * rad_per_px / stretch + tan_per_px_y * tan_per_px_y / (stretch * stretch));
}

}  // namespace

CylindricalProjection::CylindricalProjection(int width_px, int height_px, const CylindricalParameters& parameters)
    : ClosedFormProjection(width_px, height_px), parameters_(parameters) {
  const CylindricalParameters& p = parameters_;
  check_range("horizontal_fov_deg", p.horizontal_fov_deg, 0.0, true, 360.0, false);
  check_range("down_deg", p.down_deg, -kMaxEdgeDeg, true, kMaxEdgeDeg, true);
  check_range("up_deg", p.up_deg, -kMaxEdgeDeg, true, kMaxEdgeDeg, true);
  if (!(p.down_deg < p.up_deg))
    fail("down_deg = " + number(p.down_deg) + " must be less than up_deg = " + number(p.up_deg));
  // Yaw, pitch and roll in [−360, 360], kept normalized (as PlanarFrustum's).
  check_and_normalize_orientation(parameters_, "CylindricalProjection");

  tan_down_ = std::tan(p.down_deg * kDeg);
  tan_up_ = std::tan(p.up_deg * kDeg);
  rad_per_px_ = p.horizontal_fov_deg * kDeg / width_px;
  tan_per_px_y_ = (tan_down_ - tan_up_) / height_px;
  // Half a turn in pixels, from the degrees so that a 360° cylinder gets exactly
  // width / 2 (π / k_φ may round either way).
  half_turn_px_ = 0.5 * width_px * (360.0 / p.horizontal_fov_deg);
  // The same frame as a PlanarFrustum with these yaw, pitch and roll (the edge
  // angles do not enter the rotation).
  rotation_ =
      PlanarProjection(1, 1, PlanarFrustum{-1.0, 1.0, -1.0, 1.0, p.yaw_deg, p.pitch_deg, p.roll_deg}).rotation();

  set_closed_form(
      cylindrical_gpu(rotation_, tan_down_, tan_up_, rad_per_px_, tan_per_px_y_, half_turn_px_, width_px, height_px),
      cylindrical_description(p, width_px, height_px),
      cylindrical_max_pixel_angle_rad(tan_down_, tan_up_, rad_per_px_, tan_per_px_y_));
}

std::optional<glm::dvec3> CylindricalProjection::ray(double x_px, double y_px) const {
  if (!std::isfinite(x_px) || !std::isfinite(y_px)) return std::nullopt;
  const double from_centre_px = x_px - 0.5 * width();
  if (std::abs(from_centre_px) > half_turn_px_) return std::nullopt;
  const double phi = from_centre_px * rad_per_px_;
  const double v = tan_up_ + y_px * tan_per_px_y_;
  // The point of the unit cylinder (cylinder frame) that the pixel shows.
  const glm::dvec3 on_cylinder(std::sin(phi), v, -std::cos(phi));
  return glm::normalize(rotation_ * on_cylinder);
}

std::optional<glm::dvec2> CylindricalProjection::pixel(const glm::dvec3& direction) const {
  if (!std::isfinite(direction.x) || !std::isfinite(direction.y) || !std::isfinite(direction.z)) return std::nullopt;
  // Into the cylinder frame: Rᵀ · d.
  const glm::dvec3 d(glm::dot(rotation_[0], direction), glm::dot(rotation_[1], direction),
                     glm::dot(rotation_[2], direction));
  const double across = std::hypot(d.x, d.z);  // distance from the cylinder's axis
  if (across == 0.0) return std::nullopt;      // a pole, or the zero vector
  const double phi = std::atan2(d.x, -d.z);    // in [−π, π], 0 forward, π/2 right
  double x_px = 0.5 * width() + phi / rad_per_px_;
  if (parameters_.horizontal_fov_deg == 360.0) {
    // One column of rays at x = 0 and x = width: keep [0, width).
    if (x_px >= width()) x_px -= width();
    if (x_px < 0.0) x_px = std::max(0.0, x_px + width());
    if (x_px >= width()) x_px = 0.0;  // −tiny + width rounded up to width
  }
  const double v = d.y / across;
  return glm::dvec2(x_px, (v - tan_up_) / tan_per_px_y_);
}

}  // namespace zenith::warp
