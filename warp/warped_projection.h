#pragma once
// A projector seen through a warp mesh: the projector's pixel (x, y) shows what
// the base projection (the dome master fisheye, or a frustum) has at the source
// point the mesh gives:
//
//   (s, t) = (x / width, y / height)                   the projector's image, normalized
//   (u, v) = mesh.sample(s, t)                          the base image, normalized
//   ray(x, y) = base.ray(u · base.width, v · base.height)
//
// so rendering through a WarpedProjection renders the warped image directly:
// no intermediate dome master, no resampling of pixels. Where the mesh has no
// data, there is no ray (the renderer leaves the pixel black), and
// intensity(x, y) gives the mesh's brightness factor, which the output stage
// applies. docs/warp-meshes.md has the formats and the interpolation.
#include <memory>
#include <vector>

#include <glm/vec4.hpp>

#include "warp/projection.h"
#include "warp/warp_mesh.h"

namespace zenith::warp {

class WarpedProjection final : public Projection {
 public:
  /// A width_px × height_px projector image. Throws std::invalid_argument for a
  /// size outside [1, 65536] and a null base.
  WarpedProjection(int width_px, int height_px, WarpMesh mesh, std::shared_ptr<const Projection> base);

  const WarpMesh& mesh() const { return mesh_; }
  const Projection& base() const { return *base_; }

  /// The base image position (pixels) the projector's pixel position shows;
  /// nothing where the mesh has no data.
  std::optional<glm::dvec2> source_pixel(double x_px, double y_px) const;
  /// The mesh's intensity in [0, 1] at the projector's pixel position; 0 where
  /// the mesh has no data.
  double intensity(double x_px, double y_px) const;

  /// base.ray() of source_pixel(); nothing where the mesh has no data or the
  /// base projection has no ray.
  std::optional<glm::dvec3> ray(double x_px, double y_px) const override;
  /// Numerical inverse: the base's pixel() gives the source point (u, v); the
  /// projector point with mesh(s, t) = (u, v) is found by Newton's method (central
  /// differences) started from the nearest of a coarse set of nodes (at most
  /// 64 × 64), then from the next three nearest if that fails; converged when
  /// the source points agree within 1e-7 base px. Nothing when the base does not
  /// see the direction or no start converges (the direction is outside the mesh).
  /// Where the mesh folds over itself, one of the preimages is returned.
  std::optional<glm::dvec2> pixel(const glm::dvec3& direction) const override;
  /// ProjectionKind::ray_table: a mesh has no closed form in
  /// shaders/projection.glsl, so the renderer tabulates ray() per band (in double).
  GpuProjection gpu() const override;
  /// "warped 1920×1080 (mesh 33×33 catmull-rom from dome.data) over fisheye 180° 2048×2048".
  std::string describe() const override;
  /// base.max_pixel_angle_rad() · max(1, k) · 1.25, k the largest stretch of the
  /// mesh (base pixels per projector pixel between neighbouring valid nodes,
  /// along rows, columns and diagonals) among the nodes that reach the image;
  /// 1.25 covers the cubic's bulge between nodes. Relies on the base bound
  /// growing linearly with distance (as the fisheye's and the planar bounds
  /// do). A worst case over the image, nodes parked far away included:
  /// max_pixel_angle_rad_within() of the whole image.
  double max_pixel_angle_rad() const override;
  /// The same bound with k taken over the nodes whose interpolation reaches
  /// the rectangle only: the grid cells the rectangle overlaps and one more
  /// node on each side (the 4 × 4 nodes of a Catmull–Rom cell; the linear
  /// extrapolation past the mesh's border adds no new differences). So a node
  /// parked far away (Bourke's unused nodes at (0, 0)) widens the culling of
  /// the tiles its cells reach, not of the others; the pixels of those tiles
  /// do show rays that sweep across the source, so they keep the large bound.
  /// The rectangle is clipped to the image first; one that holds no pixel of
  /// the image or misses the mesh: base.max_pixel_angle_rad() · 1.25.
  double max_pixel_angle_rad_within(double x0_px, double y0_px, double x1_px, double y1_px) const override;
  /// The footprint of the projector pixel the direction lands in:
  ///
  ///   base.pixel_angle_rad_at(direction) · σ_max(J),
  ///   J = ∂(source px) / ∂(projector px) by central differences over ±½ px,
  ///
  /// σ_max the largest singular value of the 2 × 2 Jacobian, i.e. the longest a
  /// projector pixel's unit side or diagonal-per-√2 becomes in base pixels (a
  /// pixel maps to the parallelogram J·[−½, ½]², whose diagonal is at most
  /// √2 σ_max base pixels; the base bound already covers √2 base pixels). Only
  /// the mesh around that pixel counts, so nodes parked far away (Bourke's
  /// unused nodes at (0, 0)) do not widen it; no bulge margin is needed, the
  /// differences are taken of the interpolated mesh itself. Where the direction
  /// misses the mesh (a sun just off the frame) the footprint is that of the
  /// valid coarse node whose ray is nearest to it; max_pixel_angle_rad() only
  /// when no node has a ray.
  double pixel_angle_rad_at(const glm::dvec3& direction) const override;
  /// σ_max(J) at the projector pixel position (x, y) (see pixel_angle_rad_at),
  /// one-sided where a side has no data; nothing where neither side has data
  /// along x or along y.
  std::optional<double> local_stretch(double x_px, double y_px) const;

 private:
  std::optional<glm::dvec2> source_uv(double s, double t) const;
  /// The largest stretch (base px per projector px) between neighbouring valid
  /// nodes (rows, columns, diagonals), both within columns [i0, i1] and rows [j0, j1].
  double stretch_between_nodes(int i0, int i1, int j0, int j1) const;
  /// base.max_pixel_angle_rad() · max(1, stretch) · the bulge margin.
  double pixel_angle_bound(double stretch) const;
  /// pixel_angle_bound() of the nodes that reach the rectangle (finite, within
  /// the image, x0 < x1, y0 < y1).
  double bound_within(double x0_px, double y0_px, double x1_px, double y1_px) const;

  WarpMesh mesh_;
  std::shared_ptr<const Projection> base_;
  double max_pixel_angle_rad_ = 0.0;
  std::vector<glm::dvec4> coarse_nodes_;  // (s, t, u, v) of the valid nodes the inverse starts from
};

}  // namespace zenith::warp
