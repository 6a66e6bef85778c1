#pragma once
// Which 16×16-pixel tiles of an image a sphere (an atmosphere's shell, a body)
// can touch, so a pass covers only those pixels.
//
// A tile's rays fill a cone: TileCones computes, once per projection, each
// tile's cone in the camera frame (axis and half-angle) from the rays of the
// ring of pixel centres on the tile's border (for the continuous projections
// here the border's rays enclose the interior's), widened by one pixel's angle
// (the projection's bound over the tile's pixels, max_pixel_angle_rad_within:
// through a warp mesh, the bound of the mesh nodes that reach the tile).
// A sphere of radius R at distance D in direction ĉ can touch the tile when
//   angle(axis, ĉ) ≤ half_angle + asin(R / D),
// and always when the camera is inside it (D ≤ R). Tiles whose border has no
// ray at all (outside a fisheye's circle) hold no pixel with a ray: never listed.
//
// The tests run per frame for every sphere and band, on the frame's critical
// path (262 144 tiles on an 8192² dome master). So that they cost the sphere's
// outline rather than the image, the tiles are grouped in blocks of
// kTileBlock × kTileBlock whose cone holds every tile's cone (triangle
// inequality: angle(block axis, tile axis) + tile half-angle ≤ block
// half-angle, padded by kBlockMarginRad for the rounding of those angles). A
// block whose cone misses the sphere holds no touching tile; one whose cone
// lies within the sphere's disc holds only `all` tiles; only the blocks the
// limb crosses are tested tile by tile, with the same arithmetic as a lone
// tile, so the result is the tile-by-tile one exactly.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "warp/projection.h"

namespace zenith::render {

inline constexpr int kTileSize = 16;  ///< pixels; the local size of the render passes
inline constexpr int kTileBlock = 8;  ///< tiles per side of a block of the culling hierarchy
/// Rounding allowance of a block's cone [rad]: the computed angles (2 asin(|a − b| / 2)
/// of unit vectors in double) err by under 3e-8 rad even next to antipodes.
inline constexpr double kBlockMarginRad = 1e-6;

/// A tile of a band's tile list as one 32-bit word (the render passes' Tiles
/// buffer, shaders/render/frame.glsl's tile_pixel()): its column in the low
/// kTileRowShift bits, its row within the band above them. The shaders get
/// both constants as TILE_ROW_SHIFT and TILE_COLUMN_MASK
/// (render/shader_bindings.h's shader_interface_defines()).
inline constexpr unsigned kTileRowShift = 16;
inline constexpr std::uint32_t kTileColumnMask = (std::uint32_t{1} << kTileRowShift) - 1u;
constexpr std::uint32_t pack_tile(std::uint32_t column, std::uint32_t band_row) {
  return column | band_row << kTileRowShift;
}
constexpr std::uint32_t tile_column(std::uint32_t word) { return word & kTileColumnMask; }
constexpr std::uint32_t tile_band_row(std::uint32_t word) { return word >> kTileRowShift; }

/// How a tile's rays meet a sphere (TileCones::sphere_cover).
enum class TileCover : std::uint8_t {
  none = 0,  ///< no ray of the tile can meet it
  all = 1,   ///< every ray meets it: the tile's cone lies within the sphere's disc
  some = 2,  ///< some may
};

/// A tile's cone of rays, camera frame.
struct TileCone {
  glm::vec3 axis{0.0f, 0.0f, -1.0f};  ///< unit
  float half_angle_rad = 0.0f;
  bool has_rays = false;
};

/// The angle between two unit vectors [rad], 2 asin(|a − b| / 2): accurate at
/// small angles, where the tests of culling are decided.
double angle_between_units(const glm::dvec3& a, const glm::dvec3& b);

class TileCones {
 public:
  /// Computes every tile's cone (O(pixels on tile borders) projection calls).
  explicit TileCones(const warp::Projection& projection);

  int columns() const { return columns_; }
  int rows() const { return rows_; }
  const TileCone& cone(int column, int row) const { return cones_[static_cast<std::size_t>(row) * columns_ + column]; }

  /// Tiles of rows [first_row, first_row + row_count) that a sphere (camera-frame
  /// unit direction to its centre, distance and radius in metres) can touch,
  /// packed by pack_tile (the tile's column and its row within the band).
  std::vector<std::uint32_t> tiles_touching_sphere(const glm::dvec3& centre_direction, double distance_m,
                                                   double radius_m, int first_row, int row_count) const;
  /// For every tile of rows [first_row, first_row + row_count), column fastest,
  /// how its rays meet the sphere: `all` when the cone, widened by 1e-4 rad,
  /// lies within the sphere's angular disc (or the camera is inside the sphere).
  std::vector<TileCover> sphere_cover(const glm::dvec3& centre_direction, double distance_m, double radius_m,
                                      int first_row, int row_count) const;

 private:
  /// A block's cone (camera frame), holding the cones of its tiles with rays.
  struct BlockCone {
    glm::dvec3 axis{0.0, 0.0, -1.0};
    double half_angle_rad = 0.0;
    bool has_rays = false;
  };
  /// How one tile's rays meet a sphere of `angular_radius_rad` in direction `c`.
  static TileCover cover_of(const TileCone& cone, const glm::dvec3& c, double angular_radius_rad);

  int columns_ = 0, rows_ = 0;
  std::vector<TileCone> cones_;
  int block_columns_ = 0, block_rows_ = 0;
  std::vector<BlockCone> blocks_;
};

}  // namespace zenith::render
