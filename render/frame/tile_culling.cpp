#include "render/frame/tile_culling.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/parallel_for.h"

namespace zenith::render {

TileCones::TileCones(const warp::Projection& projection)
    : columns_((projection.width() + kTileSize - 1) / kTileSize),
      rows_((projection.height() + kTileSize - 1) / kTileSize),
      cones_(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_)) {
  // Rows of tiles on every core: an 8192² dome master's 512 × 512 tiles take
  // 15.7 M border rays, all before the projection's first frame (each tile is
  // its own; Projection is const). Timed by bench/tile_cones_bench.
  core::parallel_for(static_cast<std::size_t>(rows_), 0, [&](std::size_t row) {
    const int ty = static_cast<int>(row);
    std::vector<glm::dvec3> rays;
    rays.reserve(4 * kTileSize);
    for (int tx = 0; tx < columns_; ++tx) {
      const int x0 = tx * kTileSize, y0 = ty * kTileSize;
      const int x1 = std::min(x0 + kTileSize, projection.width()) - 1;
      const int y1 = std::min(y0 + kTileSize, projection.height()) - 1;
      rays.clear();
      auto add = [&](int x, int y) {
        if (auto r = projection.ray(x + 0.5, y + 0.5)) rays.push_back(glm::normalize(*r));
      };
      for (int x = x0; x <= x1; ++x) {
        add(x, y0);
        if (y1 != y0) add(x, y1);
      }
      for (int y = y0 + 1; y < y1; ++y) {
        add(x0, y);
        if (x1 != x0) add(x1, y);
      }
      TileCone& cone = cones_[static_cast<std::size_t>(ty) * columns_ + tx];
      if (rays.empty()) continue;
      // The tile's own bound: through a warp mesh, a node parked far away
      // widens the tiles its cells reach, not every tile.
      const double margin = projection.max_pixel_angle_rad_within(x0, y0, x1 + 1, y1 + 1);
      glm::dvec3 sum(0.0);
      for (const glm::dvec3& r : rays) sum += r;
      // Rays spread over more than a hemisphere (a 360° fisheye's rim): the cone is everything.
      const double length = glm::length(sum);
      glm::dvec3 axis = length > 1e-9 ? sum / length : rays.front();
      // The angle 2 asin(|r − axis| / 2) grows with the chord: one asin, of the longest.
      double chord = 0.0;
      for (const glm::dvec3& r : rays) chord = std::max(chord, glm::length(r - axis));
      const double half_angle = 2.0 * std::asin(std::min(1.0, 0.5 * chord));
      cone.axis = glm::vec3(axis);
      cone.half_angle_rad = static_cast<float>(length > 1e-9 ? half_angle + margin : 4.0);
      cone.has_rays = true;
    }
  });
  // Blocks of kTileBlock² tiles: the axis is the mean of the tiles' axes, the
  // half-angle the farthest tile cone's edge from it (triangle inequality), padded.
  block_columns_ = (columns_ + kTileBlock - 1) / kTileBlock;
  block_rows_ = (rows_ + kTileBlock - 1) / kTileBlock;
  blocks_.assign(static_cast<std::size_t>(block_columns_) * static_cast<std::size_t>(block_rows_), BlockCone{});
  for (int by = 0; by < block_rows_; ++by)
    for (int bx = 0; bx < block_columns_; ++bx) {
      const int tx0 = bx * kTileBlock, tx1 = std::min(columns_, tx0 + kTileBlock);
      const int ty0 = by * kTileBlock, ty1 = std::min(rows_, ty0 + kTileBlock);
      BlockCone& block = blocks_[static_cast<std::size_t>(by) * block_columns_ + bx];
      glm::dvec3 sum(0.0);
      for (int ty = ty0; ty < ty1; ++ty)
        for (int tx = tx0; tx < tx1; ++tx)
          if (cone(tx, ty).has_rays) {
            sum += glm::dvec3(cone(tx, ty).axis);
            block.has_rays = true;
          }
      if (!block.has_rays) continue;
      const double length = glm::length(sum);
      if (!(length > 1e-9)) {  // tiles all round the sphere of directions: tested one by one
        block.half_angle_rad = 10.0;
        continue;
      }
      block.axis = sum / length;
      double half_angle = 0.0;
      for (int ty = ty0; ty < ty1; ++ty)
        for (int tx = tx0; tx < tx1; ++tx) {
          const TileCone& c = cone(tx, ty);
          if (c.has_rays)
            half_angle = std::max(half_angle, angle_between_units(block.axis, glm::dvec3(c.axis)) +
                                                  static_cast<double>(c.half_angle_rad));
        }
      block.half_angle_rad = half_angle + kBlockMarginRad;
    }
}

double angle_between_units(const glm::dvec3& a, const glm::dvec3& b) {
  return 2.0 * std::asin(std::min(1.0, 0.5 * glm::length(a - b)));
}

TileCover TileCones::cover_of(const TileCone& cone, const glm::dvec3& c, double angular_radius_rad) {
  const double angle = angle_between_units(glm::dvec3(cone.axis), c);
  // 1e-4 rad covers the float axis stored in the cone.
  if (angle > cone.half_angle_rad + angular_radius_rad + 1e-4) return TileCover::none;
  return angle + cone.half_angle_rad + 1e-4 <= angular_radius_rad ? TileCover::all : TileCover::some;
}

std::vector<std::uint32_t> TileCones::tiles_touching_sphere(const glm::dvec3& centre_direction, double distance_m,
                                                            double radius_m, int first_row, int row_count) const {
  const std::vector<TileCover> cover = sphere_cover(centre_direction, distance_m, radius_m, first_row, row_count);
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < cover.size(); ++i)
    if (cover[i] != TileCover::none) {
      const auto tx = static_cast<std::uint32_t>(i % static_cast<std::size_t>(columns_));
      const auto band_ty = static_cast<std::uint32_t>(i / static_cast<std::size_t>(columns_));
      out.push_back(pack_tile(tx, band_ty));
    }
  return out;
}

std::vector<TileCover> TileCones::sphere_cover(const glm::dvec3& centre_direction, double distance_m, double radius_m,
                                               int first_row, int row_count) const {
  const int tile_row_begin = first_row / kTileSize;
  const int tile_row_end = std::min(rows_, (first_row + row_count + kTileSize - 1) / kTileSize);
  std::vector<TileCover> out(static_cast<std::size_t>(std::max(0, tile_row_end - tile_row_begin)) * columns_,
                             TileCover::none);
  const bool inside = distance_m <= radius_m;
  const double angular_radius = inside ? 4.0 : std::asin(radius_m / distance_m);
  const glm::dvec3 c = glm::normalize(centre_direction);
  for (int by = tile_row_begin / kTileBlock; by * kTileBlock < tile_row_end; ++by)
    for (int bx = 0; bx < block_columns_; ++bx) {
      const BlockCone& block = blocks_[static_cast<std::size_t>(by) * block_columns_ + bx];
      if (!block.has_rays) continue;
      // The block's verdict where its cone decides it (every tile's would be
      // the same, kBlockMarginRad covering the rounding), else tile by tile.
      bool decided = inside;
      if (!inside) {
        const double angle = angle_between_units(block.axis, c);
        if (angle > block.half_angle_rad + angular_radius + 1e-4) continue;
        decided = angle + block.half_angle_rad + 1e-4 <= angular_radius;
      }
      const int ty0 = std::max(tile_row_begin, by * kTileBlock), ty1 = std::min(tile_row_end, (by + 1) * kTileBlock);
      const int tx0 = bx * kTileBlock, tx1 = std::min(columns_, tx0 + kTileBlock);
      for (int ty = ty0; ty < ty1; ++ty)
        for (int tx = tx0; tx < tx1; ++tx) {
          const TileCone& cone = this->cone(tx, ty);
          if (!cone.has_rays) continue;
          out[static_cast<std::size_t>(ty - tile_row_begin) * columns_ + tx] =
              decided ? TileCover::all : cover_of(cone, c, angular_radius);
        }
    }
  return out;
}

}  // namespace zenith::render
