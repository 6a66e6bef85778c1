#include "warp/equirectangular_projection.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "core/units.h"

namespace zenith::warp {
namespace {

using core::kDeg;
using core::kPi;

/// The shortest text that reads back as `value` ("-180", "89.5").
std::string number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("EquirectangularProjection: " + what); }

/// Requires value in [lo, hi]; NaN and infinities fail.
void check_range(const char* name, double value, double lo, double hi) {
  if (!(lo <= value && value <= hi))
    fail(std::string(name) + " = " + number(value) + ": must be in [" + number(lo) + ", " + number(hi) + "] degrees");
}

/// EquirectangularProjection's describe().
std::string equirectangular_description(const EquirectangularParameters& p, int width_px, int height_px) {
  std::ostringstream out;  // 6 significant digits
  out << "equirectangular " << p.longitude_max_deg - p.longitude_min_deg << "°×"
      << p.latitude_max_deg - p.latitude_min_deg << "° (longitude " << p.longitude_min_deg << "° to "
      << p.longitude_max_deg << "°, latitude " << p.latitude_min_deg << "° to " << p.latitude_max_deg << "°) "
      << width_px << "×" << height_px;
  return out.str();
}

/// EquirectangularProjection's max_pixel_angle_rad(), with k_λ = `rad_per_px_x`
/// and k_β = `rad_per_px_y`.
double equirectangular_max_pixel_angle_rad(const EquirectangularParameters& p, double rad_per_px_x,
                                           double rad_per_px_y) {
  // The sphere's metric dβ² + cos²β dλ² is largest across where |β| is smallest;
  // a straight segment between two points of one pixel stays in the image
  // rectangle and moves at most one pixel in x and in y.
  const double nearest_latitude_rad = std::clamp(0.0, p.latitude_min_deg, p.latitude_max_deg) * kDeg;
  const double across = std::cos(nearest_latitude_rad) * rad_per_px_x;
  return std::hypot(across, rad_per_px_y);
}

}  // namespace

EquirectangularProjection::EquirectangularProjection(int width_px, int height_px,
                                                     const EquirectangularParameters& parameters)
    : ClosedFormProjection(width_px, height_px), parameters_(parameters) {
  const EquirectangularParameters& p = parameters;
  check_range("longitude_min_deg", p.longitude_min_deg, -360.0, 360.0);
  check_range("longitude_max_deg", p.longitude_max_deg, -360.0, 360.0);
  if (!(p.longitude_min_deg < p.longitude_max_deg))
    fail("longitude_min_deg = " + number(p.longitude_min_deg) +
         " must be less than longitude_max_deg = " + number(p.longitude_max_deg));
  if (!(p.longitude_max_deg - p.longitude_min_deg <= 360.0))
    fail("longitude_max_deg − longitude_min_deg = " + number(p.longitude_max_deg - p.longitude_min_deg) +
         ": must be in (0, 360] degrees (longitude_min_deg = " + number(p.longitude_min_deg) +
         ", longitude_max_deg = " + number(p.longitude_max_deg) + ")");
  check_range("latitude_min_deg", p.latitude_min_deg, -90.0, 90.0);
  check_range("latitude_max_deg", p.latitude_max_deg, -90.0, 90.0);
  if (!(p.latitude_min_deg < p.latitude_max_deg))
    fail("latitude_min_deg = " + number(p.latitude_min_deg) +
         " must be less than latitude_max_deg = " + number(p.latitude_max_deg));

  const double longitude_range_deg = p.longitude_max_deg - p.longitude_min_deg;
  centre_longitude_rad_ = 0.5 * (p.longitude_min_deg + p.longitude_max_deg) * kDeg;
  centre_latitude_rad_ = 0.5 * (p.latitude_min_deg + p.latitude_max_deg) * kDeg;
  rad_per_px_x_ = longitude_range_deg * kDeg / width_px;
  rad_per_px_y_ = -(p.latitude_max_deg - p.latitude_min_deg) * kDeg / height_px;
  half_turn_px_ = 0.5 * width_px * (360.0 / longitude_range_deg);  // exactly width / 2 for 360°

  GpuProjection gpu;
  gpu.kind = ProjectionKind::equirectangular;
  gpu.params = {
      std::array<float, 4>{static_cast<float>(0.5 * width_px), static_cast<float>(rad_per_px_x_),
                           static_cast<float>(0.5 * height_px), static_cast<float>(rad_per_px_y_)},
      std::array<float, 4>{static_cast<float>(centre_longitude_rad_), static_cast<float>(centre_latitude_rad_),
                           static_cast<float>(half_turn_px_), static_cast<float>(0.5 * kPi)},
      std::array<float, 4>{}, std::array<float, 4>{}};
  set_closed_form(gpu, equirectangular_description(p, width_px, height_px),
                  equirectangular_max_pixel_angle_rad(p, rad_per_px_x_, rad_per_px_y_));
}

std::optional<glm::dvec3> EquirectangularProjection::ray(double x_px, double y_px) const {
  if (!std::isfinite(x_px) || !std::isfinite(y_px)) return std::nullopt;
  const double from_centre_px = x_px - 0.5 * width();
  if (std::abs(from_centre_px) > half_turn_px_) return std::nullopt;
  // The latitude in degrees, interpolated so that the top and bottom edges get
  // latitude_max and latitude_min exactly (a pole row must not fall past 90°).
  const double t = y_px / height();
  const double latitude_deg = (1.0 - t) * parameters_.latitude_max_deg + t * parameters_.latitude_min_deg;
  if (!(std::abs(latitude_deg) <= 90.0)) return std::nullopt;
  const double lambda = centre_longitude_rad_ + from_centre_px * rad_per_px_x_;
  const double beta = latitude_deg * kDeg;
  const double cos_beta = std::cos(beta);
  return glm::normalize(glm::dvec3(cos_beta * std::sin(lambda), std::sin(beta), -cos_beta * std::cos(lambda)));
}

std::optional<glm::dvec2> EquirectangularProjection::pixel(const glm::dvec3& d) const {
  if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z)) return std::nullopt;
  const double across = std::hypot(d.x, d.z);  // distance from the ±y axis
  if (across == 0.0 && d.y == 0.0) return std::nullopt;
  const double beta = std::atan2(d.y, across);  // [−π/2, π/2], accurate at the poles
  double x_px = 0.5 * width();                  // straight up or down: the middle column
  if (across > 0.0) {
    // λ within half a turn of the range's middle, as λ − λ_c ∈ [−π, π].
    const double lambda = std::atan2(d.x, -d.z);
    const double from_centre_rad = std::remainder(lambda - centre_longitude_rad_, 2.0 * kPi);
    x_px += from_centre_rad / rad_per_px_x_;
    if (parameters_.longitude_max_deg - parameters_.longitude_min_deg == 360.0) {
      // One column of rays at x = 0 and x = width: keep [0, width).
      if (x_px >= width()) x_px -= width();
      if (x_px < 0.0) x_px = std::max(0.0, x_px + width());
      if (x_px >= width()) x_px = 0.0;  // −tiny + width rounded up to width
    }
  }
  return glm::dvec2(x_px, 0.5 * height() + (beta - centre_latitude_rad_) / rad_per_px_y_);
}

}  // namespace zenith::warp
