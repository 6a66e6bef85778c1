#include "warp/projection.h"

#include <stdexcept>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

namespace zenith::warp {
namespace {

constexpr int kMinSizePx = 1;
constexpr int kMaxSizePx = 65536;  // 8K domes are 8192 px; 65536 leaves room and keeps float pixel maths exact

void check_size(const char* name, int value_px) {
  if (value_px < kMinSizePx || value_px > kMaxSizePx)
    throw std::invalid_argument(std::string("projection ") + name + " = " + std::to_string(value_px) +
                                ": must be in [" + std::to_string(kMinSizePx) + ", " + std::to_string(kMaxSizePx) +
                                "] px");
}

}  // namespace

Projection::Projection(int width_px, int height_px) : width_(width_px), height_(height_px) {
  check_size("width_px", width_px);
  check_size("height_px", height_px);
}

double Projection::pixel_solid_angle_by_rays_sr(double x_px, double y_px) const {
  const auto xa = ray(x_px - 0.5, y_px), xb = ray(x_px + 0.5, y_px);
  const auto ya = ray(x_px, y_px - 0.5), yb = ray(x_px, y_px + 0.5);
  if (!xa || !xb || !ya || !yb) return 0.0;
  return glm::length(glm::cross(glm::normalize(*xb) - glm::normalize(*xa), glm::normalize(*yb) - glm::normalize(*ya)));
}

void ClosedFormProjection::set_closed_form(const GpuProjection& gpu, std::string description,
                                           double max_pixel_angle_rad) {
  gpu_ = gpu;
  description_ = std::move(description);
  max_pixel_angle_rad_ = max_pixel_angle_rad;
}

std::array<float, 4> gpu_vec4(const glm::dvec3& v, double w) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z), static_cast<float>(w)};
}

}  // namespace zenith::warp
