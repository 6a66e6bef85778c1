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

/// CubeFaceProjection's gpu() (the layout documented there).
GpuProjection cube_face_gpu(const glm::dmat3& frame, int size_px) {
  const double centre_px = 0.5 * size_px;
  GpuProjection out;
  out.kind = ProjectionKind::cube_face;
  out.params = {gpu_vec4(frame[0] * (2.0 / size_px), centre_px), gpu_vec4(frame[1] * (2.0 / size_px), centre_px),
                gpu_vec4(frame[2], 0.0), std::array<float, 4>{}};
  return out;
}

}  // namespace

std::string_view cube_face_name(CubeFace face) { return kFaces[static_cast<std::size_t>(checked_index(face))].name; }

std::optional<CubeFace> cube_face_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kFaces.size(); ++i)
    if (kFaces[i].name == name) return static_cast<CubeFace>(i);
  return std::nullopt;
}

CubeFaceProjection::CubeFaceProjection(int size_px, CubeFace face)
    : ClosedFormProjection(size_px, size_px), face_(face) {
  const FaceFrame& f = kFaces[static_cast<std::size_t>(checked_index(face))];
  frame_ = glm::dmat3(f.e_s, f.e_t, f.axis);
  const std::string size = std::to_string(size_px);
  // PlanarProjection's pixel-angle bound with the axis inside the face (ρ = 0):
  // a displacement δ on the plane at unit distance turns the ray by at most |δ|.
  set_closed_form(cube_face_gpu(frame_, size_px), "cube face " + std::string(f.name) + " " + size + "×" + size,
                  std::numbers::sqrt2 * 2.0 / size_px);
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

}  // namespace zenith::warp
