#pragma once
// One face of a cube map centred on the camera: a 90° × 90° square central
// projection onto the face z' = 1 of the cube [−1, 1]³, with the face's texel
// orientation of the OpenGL cube map (OpenGL 4.6 core, §8.13 "Cube Map Texture
// Selection", table 8.19; Vulkan, Direct3D and KTX use the same one). The
// faces are the camera frame's axes (+x right, +y up, −z forward).
// docs/projections.md has the table and the unfolded cube.
//
// OpenGL picks the face of a direction r by its major axis m = r · axis and
// reads the texel at
//
//   s = (sc / |m| + 1) / 2,   t = (tc / |m| + 1) / 2
//
//   face  axis         sc     tc      e_s (s grows)   e_t (t grows)
//   +x    (+1, 0, 0)   −r.z   −r.y    −z              −y
//   −x    (−1, 0, 0)   +r.z   −r.y    +z              −y
//   +y    (0, +1, 0)   +r.x   +r.z    +x              +z
//   −y    (0, −1, 0)   +r.x   −r.z    +x              −z
//   +z    (0, 0, +1)   +r.x   −r.y    +x              −y
//   −z    (0, 0, −1)   −r.x   −r.y    −x              −y
//
// where t = 0 is the first row of the face's image as glTexImage2D (or a KTX
// file) takes it. Here that first row is the image's top row (y = 0; pixel y
// points down), so s = x / width and t = y / height, and
//
//   ray(x, y) = normalize(axis + (2x / width − 1) · e_s + (2y / height − 1) · e_t)
//
// An image rendered with this projection (rows top to bottom, as the renderer,
// PNG and EXR store them) is uploaded unflipped as that face, and
// texture(samplerCube, r) then returns the radiance of direction r.
//
// Note that the cube map's frame is left-handed: seen from the cube's centre
// each face is a mirror image of a camera's view (+z: image right is +x and
// image up +y, where a camera looking along +z with up +y has +x on its left).
// That is the convention, not an error; it is why this is not a rotated
// PlanarProjection. A face's image up is −e_t: +y on the four side faces, −z on
// +y (the top face's top edge borders −z) and +z on −y.
#include <string_view>

#include <glm/mat3x3.hpp>

#include "warp/projection.h"

namespace zenith::warp {

/// The six faces, in OpenGL's order: GL_TEXTURE_CUBE_MAP_POSITIVE_X + face index.
enum class CubeFace : int {
  positive_x = 0,
  negative_x = 1,
  positive_y = 2,
  negative_y = 3,
  positive_z = 4,
  negative_z = 5,
};

/// "+x", "-x", "+y", "-y", "+z", "-z".
std::string_view cube_face_name(CubeFace face);
/// The face named "+x" ... "-z"; nothing for any other text.
std::optional<CubeFace> cube_face_from_name(std::string_view name);

/// What gpu(), describe() and max_pixel_angle_rad() return, computed once when
/// the projection is built (ClosedFormProjection):
///  * gpu(): kind cube_face with PlanarProjection's layout (the ray is affine in the
///    pixel, taken about the centre c = size / 2; d = (x − c) · A + (y − c) · B + C):
///      params[0] = (A = e_s · 2 / size, c)
///      params[1] = (B = e_t · 2 / size, c)
///      params[2] = (C = axis, 0)
///      params[3] = (0, 0, 0, 0)
///    Every float is exact for sizes that are powers of two.
///  * describe(): "cube face +x 512×512".
///  * max_pixel_angle_rad(): sqrt(2) · 2 / size: a central projection moves a ray by at most one
///    radian per unit of its plane (at the axis), and a pixel's diagonal is
///    sqrt(2) · 2 / size plane units long.
class CubeFaceProjection final : public ClosedFormProjection {
 public:
  /// A face `size_px` × `size_px` pixels (cube map faces are square). Throws
  /// std::invalid_argument when the size is outside [1, 65536] px or `face` is
  /// not one of the six.
  CubeFaceProjection(int size_px, CubeFace face);

  CubeFace face() const { return face_; }
  /// Columns e_s, e_t, axis in the camera frame (a signed permutation, determinant −1).
  const glm::dmat3& frame() const { return frame_; }

  /// Defined for every finite position: positions outside the face extend its plane.
  std::optional<glm::dvec3> ray(double x_px, double y_px) const override;
  /// Nothing for directions at or beyond 90° from the face's axis (m ≤ 0), the
  /// zero vector and non-finite input. A direction lies on the face, x and y in
  /// [0, size], when its major axis is the face's; random directions fall in
  /// [0, size) × [0, size) of exactly one face.
  std::optional<glm::dvec2> pixel(const glm::dvec3& direction) const override;

 private:
  CubeFace face_;
  glm::dmat3 frame_;
};

}  // namespace zenith::warp
