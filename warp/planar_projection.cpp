#include "warp/planar_projection.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "core/units.h"
#include "warp/orientation_angles.h"

namespace zenith::warp {
namespace {

using core::kDeg;
using core::kRadToDeg;
constexpr double kMaxEdgeDeg = 89.0;  // |edge angle| < 89°: tan stays below 57.3
constexpr double kMaxSymmetricFovDeg = 2.0 * kMaxEdgeDeg;

/// The shortest text that reads back as `value` ("-30", "89.0000001").
std::string number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("PlanarProjection: " + what); }

/// Requires lo < value < hi (open) or lo <= value <= hi (closed); NaN fails both.
void check_range(const char* name, double value, double lo, double hi, bool open) {
  const bool ok = open ? (lo < value && value < hi) : (lo <= value && value <= hi);
  if (!ok)
    fail(std::string(name) + " = " + number(value) + ": must be in " + (open ? "(" : "[") + number(lo) + ", " +
         number(hi) + (open ? ")" : "]") + " degrees");
}

/// Rotation by `angle_rad` about the unit axis (right-handed: counter-clockwise
/// when the axis points at the viewer), as a column-major matrix.
glm::dmat3 rotation_about(const glm::dvec3& axis, double angle_rad) {
  // Rodrigues: R = cos·I + sin·[a]× + (1 − cos)·a aᵀ.
  const double c = std::cos(angle_rad), s = std::sin(angle_rad), t = 1.0 - c;
  const double x = axis.x, y = axis.y, z = axis.z;
  return glm::dmat3(t * x * x + c, t * x * y + s * z, t * x * z - s * y,   // column 0
                    t * x * y - s * z, t * y * y + c, t * y * z + s * x,   // column 1
                    t * x * z + s * y, t * y * z - s * x, t * z * z + c);  // column 2
}

/// The image plane of a frustum in tangent units: its edges and the extent of a pixel.
struct TangentWindow {
  double left, right, down, up;
  double per_px_x, per_px_y;  // du/dx > 0, dv/dy < 0
};

/// PlanarProjection's gpu() (the layout documented there).
GpuProjection planar_gpu(const glm::dmat3& rotation, const TangentWindow& t, int width_px, int height_px) {
  const double centre_x_px = 0.5 * width_px, centre_y_px = 0.5 * height_px;
  const glm::dvec3 a = rotation[0] * t.per_px_x;
  const glm::dvec3 b = rotation[1] * t.per_px_y;
  const glm::dvec3 c = rotation * glm::dvec3(0.5 * (t.left + t.right), 0.5 * (t.up + t.down), -1.0);  // d(x_c, y_c)
  GpuProjection out;
  out.kind = ProjectionKind::planar;
  out.params = {gpu_vec4(a, centre_x_px), gpu_vec4(b, centre_y_px), gpu_vec4(c, 0.0), std::array<float, 4>{}};
  return out;
}

/// PlanarProjection's describe().
std::string planar_description(const PlanarFrustum& f, int width_px, int height_px) {
  std::ostringstream out;  // 6 significant digits: "73.7398°"
  out << "planar " << f.right_deg - f.left_deg << "°×" << f.up_deg - f.down_deg << "° (left " << f.left_deg
      << "° right " << f.right_deg << "° down " << f.down_deg << "° up " << f.up_deg << "°) " << width_px << "×"
      << height_px;
  if (f.yaw_deg != 0.0 || f.pitch_deg != 0.0 || f.roll_deg != 0.0)
    out << ", yaw " << f.yaw_deg << "° pitch " << f.pitch_deg << "° roll " << f.roll_deg << "°";
  return out.str();
}

/// PlanarProjection's max_pixel_angle_rad().
double planar_max_pixel_angle_rad(const TangentWindow& t) {
  // A displacement δ on the plane z = −1 at distance ρ from the axis turns the ray
  // by at most |δ| / sqrt(1 + ρ²) (only the part of δ across the ray counts, and
  // the ray's point lies sqrt(1 + ρ²) from the eye). Two points of one pixel are
  // joined by a segment inside the image rectangle, no longer than the pixel's
  // diagonal, on which ρ is at least the rectangle's distance from the axis.
  const double diagonal = std::hypot(t.per_px_x, t.per_px_y);
  const double nearest_u = std::clamp(0.0, t.left, t.right);
  const double nearest_v = std::clamp(0.0, t.down, t.up);
  return diagonal / std::sqrt(1.0 + nearest_u * nearest_u + nearest_v * nearest_v);
}

}  // namespace

PlanarProjection::PlanarProjection(int width_px, int height_px, const PlanarFrustum& frustum)
    : ClosedFormProjection(width_px, height_px), frustum_(frustum) {
  check_range("left_deg", frustum.left_deg, -kMaxEdgeDeg, kMaxEdgeDeg, true);
  check_range("right_deg", frustum.right_deg, -kMaxEdgeDeg, kMaxEdgeDeg, true);
  check_range("down_deg", frustum.down_deg, -kMaxEdgeDeg, kMaxEdgeDeg, true);
  check_range("up_deg", frustum.up_deg, -kMaxEdgeDeg, kMaxEdgeDeg, true);
  if (!(frustum.left_deg < frustum.right_deg))
    fail("left_deg = " + number(frustum.left_deg) + " must be less than right_deg = " + number(frustum.right_deg));
  if (!(frustum.down_deg < frustum.up_deg))
    fail("down_deg = " + number(frustum.down_deg) + " must be less than up_deg = " + number(frustum.up_deg));
  // Yaw, pitch and roll in [−360, 360] ([0, 360) as calibration tools write
  // them), kept as the same rotation with yaw and roll in (−180, 180] and pitch
  // in [−90, 90] (warp/orientation_angles.h).
  check_and_normalize_orientation(frustum_, "PlanarProjection");

  tan_left_ = std::tan(frustum.left_deg * kDeg);
  tan_right_ = std::tan(frustum.right_deg * kDeg);
  tan_down_ = std::tan(frustum.down_deg * kDeg);
  tan_up_ = std::tan(frustum.up_deg * kDeg);
  tan_per_px_x_ = (tan_right_ - tan_left_) / width_px;
  tan_per_px_y_ = (tan_down_ - tan_up_) / height_px;

  // Yaw turns right: a right-handed turn by −ψ about +y. Pitch looks up: +θ about
  // +x. Roll banks right: a right-handed turn by +φ about the view direction −z.
  const glm::dmat3 yaw = rotation_about({0.0, 1.0, 0.0}, -frustum_.yaw_deg * kDeg);
  const glm::dmat3 pitch = rotation_about({1.0, 0.0, 0.0}, frustum_.pitch_deg * kDeg);
  const glm::dmat3 roll = rotation_about({0.0, 0.0, -1.0}, frustum_.roll_deg * kDeg);
  rotation_ = yaw * pitch * roll;

  const TangentWindow window{tan_left_, tan_right_, tan_down_, tan_up_, tan_per_px_x_, tan_per_px_y_};
  set_closed_form(planar_gpu(rotation_, window, width_px, height_px), planar_description(frustum_, width_px, height_px),
                  planar_max_pixel_angle_rad(window));
}

PlanarProjection PlanarProjection::symmetric(int width_px, int height_px, double horizontal_fov_deg) {
  if (!(horizontal_fov_deg > 0.0 && horizontal_fov_deg < kMaxSymmetricFovDeg))
    fail("horizontal_fov_deg = " + number(horizontal_fov_deg) + ": must be in (0, " + number(kMaxSymmetricFovDeg) +
         ") degrees");
  // Square pixels: the tangent extent per pixel is the same both ways.
  const double half_h_rad = 0.5 * horizontal_fov_deg * kDeg;
  const double tan_half_v = std::tan(half_h_rad) * height_px / std::max(width_px, 1);
  const double half_v_deg = std::atan(tan_half_v) * kRadToDeg;
  if (!(half_v_deg < kMaxEdgeDeg))
    fail("horizontal_fov_deg = " + number(horizontal_fov_deg) + " at " + std::to_string(width_px) + "×" +
         std::to_string(height_px) + " px gives a vertical field of view of " + number(2.0 * half_v_deg) +
         " degrees: both must be below " + number(kMaxSymmetricFovDeg) + " degrees");
  const double half_h_deg = 0.5 * horizontal_fov_deg;
  return PlanarProjection(width_px, height_px, PlanarFrustum{-half_h_deg, half_h_deg, -half_v_deg, half_v_deg});
}

std::optional<glm::dvec3> PlanarProjection::ray(double x_px, double y_px) const {
  if (!std::isfinite(x_px) || !std::isfinite(y_px)) return std::nullopt;
  // The point of the image plane z = −1 (frustum frame) that the pixel position shows.
  const glm::dvec3 on_plane(tan_left_ + x_px * tan_per_px_x_, tan_up_ + y_px * tan_per_px_y_, -1.0);
  return glm::normalize(rotation_ * on_plane);
}

std::optional<glm::dvec2> PlanarProjection::pixel(const glm::dvec3& direction) const {
  if (!std::isfinite(direction.x) || !std::isfinite(direction.y) || !std::isfinite(direction.z)) return std::nullopt;
  // Into the frustum frame: Rᵀ · d (R is a rotation), one dot product per column.
  const glm::dvec3 d(glm::dot(rotation_[0], direction), glm::dot(rotation_[1], direction),
                     glm::dot(rotation_[2], direction));
  // Central projection onto z = −1 needs the direction in front of the plane's horizon.
  if (!(d.z < 0.0)) return std::nullopt;
  const double u = d.x / -d.z, v = d.y / -d.z;
  return glm::dvec2((u - tan_left_) / tan_per_px_x_, (v - tan_up_) / tan_per_px_y_);
}

double PlanarProjection::pixel_solid_angle_sr(double x_px, double y_px) const {
  const double u = tan_left_ + x_px * tan_per_px_x_, v = tan_up_ + y_px * tan_per_px_y_;
  const double q = 1.0 + u * u + v * v;
  return std::abs(tan_per_px_x_ * tan_per_px_y_) / (q * std::sqrt(q));
}

double PlanarProjection::solid_angle_relative_bound() const {
  return 0.25 * std::max(tan_per_px_x_ * tan_per_px_x_, tan_per_px_y_ * tan_per_px_y_) * (1.0 + 1e-3) + 1e-12;
}

}  // namespace zenith::warp
