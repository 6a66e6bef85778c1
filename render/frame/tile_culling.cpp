#include "render/frame/tile_culling.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace zenith::render {

TileCones::TileCones(const warp::Projection& projection)
    : columns_((projection.width() + kTileSize - 1) / kTileSize),
      rows_((projection.height() + kTileSize - 1) / kTileSize),
      cones_(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_)) {
  std::vector<glm::dvec3> rays;
  for (int ty = 0; ty < rows_; ++ty)
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
      double half_angle = 0.0;
      for (const glm::dvec3& r : rays)
        half_angle = std::max(half_angle, 2.0 * std::asin(std::min(1.0, 0.5 * glm::length(r - axis))));
      cone.axis = glm::vec3(axis);
      cone.half_angle_rad = static_cast<float>(length > 1e-9 ? half_angle + margin : 4.0);
      cone.has_rays = true;
    }
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
  for (int ty = tile_row_begin; ty < tile_row_end; ++ty)
    for (int tx = 0; tx < columns_; ++tx) {
      const TileCone& cone = this->cone(tx, ty);
      if (!cone.has_rays) continue;
      TileCover& cover = out[static_cast<std::size_t>(ty - tile_row_begin) * columns_ + tx];
      if (inside) {
        cover = TileCover::all;
        continue;
      }
      const double angle = 2.0 * std::asin(std::min(1.0, 0.5 * glm::length(glm::dvec3(cone.axis) - c)));
      // 1e-4 rad covers the float axis stored in the cone.
      if (angle > cone.half_angle_rad + angular_radius + 1e-4) continue;
      cover = angle + cone.half_angle_rad + 1e-4 <= angular_radius ? TileCover::all : TileCover::some;
    }
  return out;
}

}  // namespace zenith::render
