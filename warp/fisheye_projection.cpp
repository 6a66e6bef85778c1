#include "warp/fisheye_projection.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "core/units.h"
#include "warp/orientation_angles.h"

namespace zenith::warp {
namespace {

using core::kDeg;
constexpr double kMaxPositionPx = 1e6;  // centre and radius: far beyond any image, finite
// pixel() accepts directions this far past fov / 2 (radians), so that the rays
// ray() gives on the rim, whose angle atan2 may round up, map back.
constexpr double kRimToleranceRad = 1e-12;

/// The shortest text that reads back as `value` ("180", "89.5").
std::string number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

/// Requires value in [lo, hi] (or (lo, hi] when `open_lo`); NaN and infinities fail.
void check_range(const char* name, double value, double lo, double hi, const char* unit, bool open_lo = false) {
  const bool ok = (open_lo ? lo < value : lo <= value) && value <= hi;
  if (!ok)
    throw std::invalid_argument(std::string("FisheyeProjection: ") + name + " = " + number(value) + ": must be in " +
                                (open_lo ? "(" : "[") + number(lo) + ", " + number(hi) + "] " + unit);
}

}  // namespace

FisheyeProjection::FisheyeProjection(int width_px, int height_px, const FisheyeParameters& parameters)
    : ClosedFormProjection(width_px, height_px),
      fov_deg_(parameters.fov_deg),
      tilt_deg_(parameters.tilt_deg),
      rotation_deg_(parameters.rotation_deg),
      centre_x_px_(parameters.centre_x_px.value_or(0.5 * width_px)),
      centre_y_px_(parameters.centre_y_px.value_or(0.5 * height_px)),
      radius_px_(parameters.radius_px.value_or(0.5 * std::min(width_px, height_px))) {
  check_range("fov_deg", fov_deg_, 1.0, 360.0, "degrees");
  // A tilt in [−360, 360] ([0, 360) as tools write it) is the same tilt
  // wrapped into (−180, 180]; the axis can turn from up to forward or
  // backward, not past them.
  check_range("tilt_deg", tilt_deg_, -kMaxOrientationDeg, kMaxOrientationDeg, "degrees");
  if (const double wrapped = wrapped_deg(tilt_deg_); std::abs(wrapped) <= 90.0) {
    tilt_deg_ = wrapped;
  } else {
    throw std::invalid_argument("FisheyeProjection: tilt_deg = " + number(tilt_deg_) +
                                ": must be in [-90, 90] degrees (or the same tilt plus or minus 360: [270, 360], "
                                "[-360, -270])");
  }
  check_range("rotation_deg", rotation_deg_, -360.0, 360.0, "degrees");
  check_range("centre_x_px", centre_x_px_, -kMaxPositionPx, kMaxPositionPx, "px");
  check_range("centre_y_px", centre_y_px_, -kMaxPositionPx, kMaxPositionPx, "px");
  check_range("radius_px", radius_px_, 0.0, kMaxPositionPx, "px", /*open_lo=*/true);

  half_fov_rad_ = 0.5 * fov_deg_ * kDeg;
  rad_per_px_ = half_fov_rad_ / radius_px_;

  // The untilted dome: axis up (+y), image right +x, image up +z (backward), so
  // forward (−z) is at the bottom. The spin turns the picture counter-clockwise
  // by ρ: the pixel offset (dx, dy) shows what the unspun image has at the offset
  // turned back by −ρ, (dx cos ρ + dy sin ρ, −dx sin ρ + dy cos ρ); collecting
  // dx and dy gives the spun basis vectors below.
  const double cos_rho = std::cos(rotation_deg_ * kDeg), sin_rho = std::sin(rotation_deg_ * kDeg);
  const glm::dvec3 right(cos_rho, 0.0, -sin_rho);  // cos ρ · x̂ − sin ρ · ẑ
  const glm::dvec3 up(sin_rho, 0.0, cos_rho);      // sin ρ · x̂ + cos ρ · ẑ
  const glm::dvec3 axis(0.0, 1.0, 0.0);
  // The tilt turns +y toward −z: a right-handed turn by −tilt about +x,
  // (x, y, z) → (x, y cos t + z sin t, −y sin t + z cos t).
  const double cos_t = std::cos(tilt_deg_ * kDeg), sin_t = std::sin(tilt_deg_ * kDeg);
  auto tilt = [&](const glm::dvec3& v) {
    return glm::dvec3(v.x, v.y * cos_t + v.z * sin_t, -v.y * sin_t + v.z * cos_t);
  };
  frame_ = glm::dmat3(tilt(right), tilt(up), tilt(axis));

  GpuProjection gpu;
  gpu.kind = ProjectionKind::fisheye;
  gpu.params = {std::array<float, 4>{static_cast<float>(centre_x_px_), static_cast<float>(centre_y_px_),
                                     static_cast<float>(rad_per_px_), static_cast<float>(half_fov_rad_)},
                gpu_vec4(frame_[0], 0.0), gpu_vec4(frame_[1], 0.0), gpu_vec4(frame_[2], 0.0)};

  std::ostringstream description;  // 6 significant digits: "73.7398°"
  description << "fisheye " << fov_deg_ << "° " << width_px << "×" << height_px;
  if (tilt_deg_ != 0.0) description << ", tilt " << tilt_deg_ << "°";
  if (rotation_deg_ != 0.0) description << ", rotation " << rotation_deg_ << "°";
  if (centre_x_px_ != 0.5 * width_px || centre_y_px_ != 0.5 * height_px ||
      radius_px_ != 0.5 * std::min(width_px, height_px))
    description << ", circle r=" << radius_px_ << " px at (" << centre_x_px_ << ", " << centre_y_px_ << ")";

  // The metric of the map is dθ² + sin²θ dφ² = k² dr² + sin²(k r) dφ² with
  // k = rad_per_px, at most k² (dr² + r² dφ²): no path turns the ray by more
  // than k radians per pixel. The straight segment between two points of one
  // pixel stays in the (convex) circle and is at most sqrt(2) px long.
  set_closed_form(gpu, description.str(), std::numbers::sqrt2 * rad_per_px_);
}

std::optional<glm::dvec3> FisheyeProjection::ray(double x_px, double y_px) const {
  if (!std::isfinite(x_px) || !std::isfinite(y_px)) return std::nullopt;
  const double dx = x_px - centre_x_px_;
  const double dy = centre_y_px_ - y_px;  // image y points down; dy points up
  const double r = std::hypot(dx, dy);
  if (r > radius_px_) return std::nullopt;
  const double theta = r * rad_per_px_;
  // sin θ / r → rad_per_px at the centre, where the azimuth is undefined.
  const double sin_theta_over_r = r > 0.0 ? std::sin(theta) / r : rad_per_px_;
  const glm::dvec3 d =
      (dx * sin_theta_over_r) * frame_[0] + (dy * sin_theta_over_r) * frame_[1] + std::cos(theta) * frame_[2];
  return glm::normalize(d);  // unit already up to rounding
}

std::optional<glm::dvec2> FisheyeProjection::pixel(const glm::dvec3& direction) const {
  if (!std::isfinite(direction.x) || !std::isfinite(direction.y) || !std::isfinite(direction.z)) return std::nullopt;
  // Into the optical frame: frameᵀ · d.
  const double lx = glm::dot(frame_[0], direction);
  const double ly = glm::dot(frame_[1], direction);
  const double lz = glm::dot(frame_[2], direction);
  const double across = std::hypot(lx, ly);
  if (across == 0.0 && lz == 0.0) return std::nullopt;  // the zero vector
  // atan2 keeps θ accurate near the axis and near its opposite, where acos is not.
  const double theta = std::atan2(across, lz);
  if (theta > half_fov_rad_ + kRimToleranceRad) return std::nullopt;
  const double r = theta / rad_per_px_;
  double dx = 0.0, dy = 0.0;
  if (across > 0.0) {
    dx = r * lx / across;
    dy = r * ly / across;
  } else if (lz < 0.0) {
    dy = -r;  // exactly opposite the axis (fov 360): the rim point below the centre
  }
  return glm::dvec2(centre_x_px_ + dx, centre_y_px_ - dy);
}

double FisheyeProjection::pixel_solid_angle_sr(double x_px, double y_px) const {
  const double dx = x_px - centre_x_px_, dy = centre_y_px_ - y_px;
  // The rays' four points lie within this of the centre: at the rim, the rays decide.
  if (std::hypot(std::abs(dx) + 0.5, std::abs(dy) + 0.5) < radius_px_ - 1.0) {
    const double a = rad_per_px_, theta = a * std::hypot(dx, dy);
    if (theta <= kClosedFormSolidAngleLimit_rad)
      return theta > 1e-4 ? a * a * std::sin(theta) / theta : a * a * (1.0 - theta * theta / 6.0);
  }
  return pixel_solid_angle_by_rays_sr(x_px, y_px);
}

}  // namespace zenith::warp
