#pragma once
// A projection gives the ray of every output pixel. The renderer asks it, per
// pixel, for a direction in the camera frame; planets are then intersected
// analytically, so no projection needs a cube map and none has seams.
//
// Conventions (docs/projections.md has the diagrams):
//  * Camera frame: +x right, +y up, −z forward (OpenGL's eye space). A camera's
//    orientation maps this frame to the world.
//  * Pixel coordinates are continuous: x to the right, y down, (0, 0) the top-left
//    corner of the image, pixel (i, j) covers [i, i+1) × [j, j+1) and its centre is
//    (i + 0.5, j + 0.5).
//  * ray() and pixel() are inverses wherever ray() is defined. Neither is
//    limited to the image rectangle: a projection's domain is its plane (planar)
//    or its image circle (fisheye), which may extend past the image's edges
//    (a cropped dome master, the renderer's filter footprint at the border).
//
// Each projection also describes itself to the GPU (GpuProjection): a kind and
// sixteen floats that shaders/projection.glsl turns into the same ray, so the
// GPU does not read a ray per pixel from memory. Angles there are in radians.
#include <array>
#include <memory>
#include <optional>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace zenith::warp {

/// The kinds shaders/projection.glsl knows: the shaders get each value as
/// PROJECTION_KIND_<NAME> (render/shader_bindings.h's shader_interface_defines()).
enum class ProjectionKind : int {
  planar = 0,           ///< pinhole with an asymmetric frustum
  fisheye = 1,          ///< angular (azimuthal equidistant) fisheye
  cylindrical = 2,      ///< cylindrical panorama: angle across, tangent up
  equirectangular = 3,  ///< longitude/latitude
  cube_face = 4,        ///< one face of a cube map (the planar layout, OpenGL face orientation)
  /// No closed form on the GPU (e.g. a warp mesh): the renderer evaluates ray()
  /// on the CPU, in double, once per projection and band, and the shader reads
  /// the rays from a table (params unused).
  ray_table = 5,
};

/// What the GPU needs to compute a projection's rays: `kind` and four vec4
/// uniforms (projection_params[0..3] in the shader); the meaning of each float is
/// documented next to each projection's gpu().
struct GpuProjection {
  ProjectionKind kind = ProjectionKind::planar;
  std::array<std::array<float, 4>, 4> params{};
};

class Projection {
 public:
  virtual ~Projection() = default;

  /// The image size in pixels, each in [1, 65536].
  int width() const { return width_; }
  int height() const { return height_; }

  /// The unit direction, in the camera frame, through the continuous pixel
  /// position (x, y); nothing where the position lies outside the projection's
  /// image (e.g. the corners of a fisheye's square).
  virtual std::optional<glm::dvec3> ray(double x_px, double y_px) const = 0;
  /// Inverse of ray(): the pixel position of a camera-frame direction (need not
  /// be unit), nothing when the projection does not see it. Positions outside
  /// [0, width) × [0, height) are returned as they are (callers clip).
  virtual std::optional<glm::dvec2> pixel(const glm::dvec3& direction) const = 0;
  /// The description shaders/projection.glsl evaluates.
  virtual GpuProjection gpu() const = 0;
  /// One line for logs: "fisheye 180° 1024×1024".
  virtual std::string describe() const = 0;
  /// An upper bound of the angle (radians) between the rays of two points of
  /// the same pixel (hence also between the rays of two adjacent pixel centres,
  /// horizontally, vertically or diagonally); the renderer widens its culling by it.
  virtual double max_pixel_angle_rad() const = 0;
  /// The pixel footprint where `direction` (camera frame, need not be unit)
  /// lands: an upper bound of the angle between the rays of two points of that
  /// pixel, in radians. What is drawn at a known direction (the sun's disc and
  /// its antialiasing) is sized from this; max_pixel_angle_rad() is the bound
  /// over the whole image, for culling only. The default returns
  /// max_pixel_angle_rad(): right for projections whose footprint varies
  /// little over the image (planar, fisheye, cylindrical, ...). A warped
  /// projection returns the footprint of the pixel the direction lands in
  /// (WarpedProjection), which can be far below its worst case.
  virtual double pixel_angle_rad_at(const glm::dvec3& direction) const {
    (void)direction;
    return max_pixel_angle_rad();
  }
  /// max_pixel_angle_rad() over the pixels of the rectangle [x0_px, x1_px) ×
  /// [y0_px, y1_px) (continuous pixel positions; a tile of pixels x0 … x1 − 1) only: what the renderer widens
  /// the culling cone of a tile with (render/frame/tile_culling.h). Never
  /// above max_pixel_angle_rad(). The default returns max_pixel_angle_rad(),
  /// right for projections whose bound varies little over the image; a warped
  /// projection bounds it from the mesh nodes whose interpolation reaches the
  /// rectangle (WarpedProjection), so a node parked far away widens only the
  /// tiles its cells reach.
  virtual double max_pixel_angle_rad_within(double x0_px, double y0_px, double x1_px, double y1_px) const {
    (void)x0_px, (void)y0_px, (void)x1_px, (void)y1_px;
    return max_pixel_angle_rad();
  }

  /// The solid angle [sr] of the pixel at the continuous position (x, y) by
  /// the rays' difference quotient: with unit rays r,
  ///   Ω_rays = |(r(x + ½, y) − r(x − ½, y)) × (r(x, y + ½) − r(x, y − ½))|,
  /// 0 where one of the four rays is missing (past a fisheye's rim).
  double pixel_solid_angle_by_rays_sr(double x_px, double y_px) const;
  /// The same from the map's Jacobian where the projection has a closed form
  /// for it (about a tenth of the cost: the equidistant fisheye, the planar
  /// view), else Ω_rays. Within solid_angle_relative_bound() of Ω_rays:
  /// |Ω/Ω_rays − 1| ≤ the bound.
  virtual double pixel_solid_angle_sr(double x_px, double y_px) const {
    return pixel_solid_angle_by_rays_sr(x_px, y_px);
  }
  /// The bound of |Ω/Ω_rays − 1| for pixel_solid_angle_sr (0: it is Ω_rays).
  virtual double solid_angle_relative_bound() const { return 0.0; }

 protected:
  Projection(int width_px, int height_px);  ///< throws std::invalid_argument unless both are in [1, 65536]

 private:
  int width_, height_;
};

/// The projections with a closed form on the GPU (every kind but ray_table:
/// planar, fisheye, cylindrical, equirectangular, cube face). Their rays follow
/// from a few parameters fixed when they are built, and so do their GPU
/// description, their log line and their pixel-angle bound: the derived
/// constructor computes those three once, last, and hands them to
/// set_closed_form(); the derived class implements ray() and pixel() only.
class ClosedFormProjection : public Projection {
 public:
  GpuProjection gpu() const final { return gpu_; }
  std::string describe() const final { return description_; }
  double max_pixel_angle_rad() const final { return max_pixel_angle_rad_; }

 protected:
  ClosedFormProjection(int width_px, int height_px) : Projection(width_px, height_px) {}
  /// What gpu(), describe() and max_pixel_angle_rad() return; called once, by
  /// the derived constructor, when its own state is complete.
  void set_closed_form(const GpuProjection& gpu, std::string description, double max_pixel_angle_rad);

 private:
  GpuProjection gpu_;
  std::string description_;
  double max_pixel_angle_rad_ = 0.0;
};

/// (v.x, v.y, v.z, w) in float: one vec4 of GpuProjection::params.
std::array<float, 4> gpu_vec4(const glm::dvec3& v, double w);

}  // namespace zenith::warp
