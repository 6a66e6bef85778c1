#include "warp/cube_face_projection.h"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace zenith::warp {
namespace {

struct FaceFrame {
  std::string_view name;
  glm::dvec3 e_s, e_t, axis;
};

/// OpenGL's table (see the header), in CubeFace order.
constexpr std::array<FaceFrame, 6> kFaces = {{
    {"+x", {0, 0, -1}, {0, -1, 0}, {+1, 0, 0}},
    {"-x", {0, 0, +1}, {0, -1, 0}, {-1, 0, 0}},
    {"+y", {+1, 0, 0}, {0, 0, +1}, {0, +1, 0}},
    {"-y", {+1, 0, 0}, {0, 0, -1}, {0, -1, 0}},
    {"+z", {+1, 0, 0}, {0, -1, 0}, {0, 0, +1}},
    {"-z", {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}},
}};

int checked_index(CubeFace face) {
  const int index = static_cast<int>(face);
  if (index < 0 || index >= static_cast<int>(kFaces.size()))
    throw std::invalid_argument("CubeFaceProjection: face = " + std::to_string(index) +
                                ": must be one of +x, -x, +y, -y, +z, -z (0 to 5)");
  return index;
}

}  // namespace

std::string_view cube_face_name(CubeFace face) { return kFaces[static_cast<std::size_t>(checked_index(face))].name; }

std::optional<CubeFace> cube_face_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kFaces.size(); ++i)
    if (kFaces[i].name == name) return static_cast<CubeFace>(i);
  return std::nullopt;
}

CubeFaceProjection::CubeFaceProjection(int size_px, CubeFace face) : Projection(size_px, size_px), face_(face) {
  const FaceFrame& f = kFaces[static_cast<std::size_t>(checked_index(face))];
  frame_ = glm::dmat3(f.e_s, f.e_t, f.axis);
}

std::optional<glm::dvec3> CubeFaceProjection::ray(double x_px, double y_px) const {
  if (!std::isfinite(x_px) || !std::isfinite(y_px)) return std::nullopt;
  // (sc, tc) / |m| on the face plane: −1 at x = 0 (y = 0), +1 at x = size.
  const double sc = 2.0 * x_px / width() - 1.0;
  const double tc = 2.0 * y_px / height() - 1.0;
  return glm::normalize(sc * frame_[0] + tc * frame_[1] + frame_[2]);
}

std::optional<glm::dvec2> CubeFaceProjection::pixel(const glm::dvec3& direction) const {
  if (!std::isfinite(direction.x) || !std::isfinite(direction.y) || !std::isfinite(direction.z)) return std::nullopt;
  // The frame is a signed permutation: these dot products are exact components.
  const double m = glm::dot(frame_[2], direction);
  if (!(m > 0.0)) return std::nullopt;
  const double sc = glm::dot(frame_[0], direction) / m;
  const double tc = glm::dot(frame_[1], direction) / m;
  return glm::dvec2(0.5 * (sc + 1.0) * width(), 0.5 * (tc + 1.0) * height());
}

GpuProjection CubeFaceProjection::gpu() const {
  const double centre_px = 0.5 * width();
  auto pack = [](const glm::dvec3& v, double w) {
    return std::array<float, 4>{static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z),
                                static_cast<float>(w)};
  };
  GpuProjection out;
  out.kind = ProjectionKind::cube_face;
  out.params = {pack(frame_[0] * (2.0 / width()), centre_px), pack(frame_[1] * (2.0 / height()), centre_px),
                pack(frame_[2], 0.0), std::array<float, 4>{}};
  return out;
}

std::string CubeFaceProjection::describe() const {
  return "cube face " + std::string(cube_face_name(face_)) + " " + std::to_string(width()) + "×" +
         std::to_string(height());
}

double CubeFaceProjection::max_pixel_angle_rad() const {
  // PlanarProjection's bound with the axis inside the face (ρ = 0): a
  // displacement δ on the plane at unit distance turns the ray by at most |δ|.
  return std::numbers::sqrt2 * 2.0 / width();
}

}  // namespace zenith::warp
