#pragma once
// Which pass draws each 16×16 tile of a band (the renderer's passes,
// render/renderer.h), from the tiles each sphere can touch
// (render/frame/tile_culling.h). No GL: the lists are plain words, uploaded by
// the renderer into its tiles buffer.
//
//   exactly one atmosphere's shell can touch a tile: one pass for that
//     atmosphere (atmosphere_tile.comp), from its sky-view table when the
//     camera is inside the shell and no other body inside the shell can be
//     in the tile, else from the 4D tables; compiled for what the tile can
//     hold (the planet's ground: none, all or some of it; other bodies;
//     the sun), since llvmpipe runs every branch a program has;
//   two or more: the G-buffer path (gbuffer.comp, the atmospheres front to
//     back, resolve.comp), which composites them;
//   none, but a body or the sun can be in it: direct_light.comp, one pass
//     (tiles only one body can be in get that body's data as uniforms);
//   nothing: black (not dispatched; zeros in the rows read back).
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "render/frame/tile_culling.h"
#include "scene/scene.h"

namespace zenith::render {

/// A run of a band's tile buffer: `count` tiles from `offset`.
struct TileList {
  std::size_t offset = 0, count = 0;
};

/// What the tiles of a one-pass list can hold: atmosphere_tile.comp is
/// compiled for each combination in use (its TILE_GROUND, TILE_OTHERS, SUN
/// and SKY_VIEW defines), since a CPU rasterizer runs every branch a program has.
struct TileVariant {
  bool sky_view = false;               ///< S from the sky-view table (camera inside the shell)
  TileCover ground = TileCover::some;  ///< how the rays meet this planet's ground
  int others = 2;                      ///< other bodies: 0 none, 1 all beyond the shell, 2 one may be inside it
  bool sun = true;                     ///< the sun's disc can be in the tiles
  /// sky_view | ground << 1 | others << 3 | sun << 5: under kVariantKeys.
  int key() const;
};
inline constexpr std::size_t kVariantKeys = 64;

/// The variant whose program draws `v`'s tiles too, with the same pixels: the
/// ground in some of each tile (TILE_GROUND 2), whose program tests every ray
/// against the planet and then computes what `v`'s program computes for it —
/// no pixel of `v`'s tiles takes the code `v`'s leaves out. One program for a shell's
/// ground, horizon and sky tiles: fewer builds where a start builds them one
/// at a time (RenderOptions::tile_programs), at the cost of running that
/// code's masked lanes (docs/shows.md, "One tile program at the start").
TileVariant general_tile_variant(TileVariant v);

/// An atmosphere's shell as the frame sees it, in the order its passes run
/// (front to back).
struct ShellInView {
  int body = 0;                      ///< its planet's index in the scene
  glm::dvec3 direction_camera{0.0};  ///< towards the planet's centre, camera frame
  double distance_m = 0.0;           ///< camera to the planet's centre
  double top_radius_m = 0.0;
  bool drawn = false;     ///< its tables are resident (false: outside the view, no tiles)
  bool sky_view = false;  ///< the camera is inside and the shell's sky-view table is filled
};

/// What the tiles of a frame can hold: the scene, the projection's tile
/// cones, the atmospheres' shells and where the sun's disc can be drawn.
struct TileScene {
  const scene::Scene* scene = nullptr;
  const TileCones* cones = nullptr;
  glm::dmat3 world_to_camera{1.0};
  glm::dvec3 sun_camera{0.0, 0.0, 1.0};  ///< the sun's direction, camera frame
  double sun_reach_rad = 0.0;            ///< the cone around it in which the sun is drawn
  bool sun_disc = true;                  ///< RenderOptions::sun_disc
  bool one_pass_tiles = true;  ///< RenderOptions::one_pass_tiles (false: every shell tile to the G-buffer path)
  std::vector<ShellInView> shells;
};

/// A band's tiles sorted by how they are drawn: the lists, one after the
/// other in one buffer (`all_tiles`, words of pack_tile), and the counts.
struct BandTiles {
  int first_row = 0, rows = 0, tile_rows = 0;
  std::size_t tiles = 0;             // tiles of the band
  std::vector<std::uint8_t> shells;  // shells that can touch the tile (saturating at 2)
  std::vector<std::uint8_t> black;   // nothing is dispatched for the tile
  /// How the tile's rays can meet bodies: none where no body's sphere touches
  /// the tile's cone, all where the cone lies within the disc of an
  /// atmosphere's planet (its ground, TileVariant::ground), some elsewhere.
  /// The night sky's pass (render/night/star_pass.h) draws only on rays that
  /// meet no body: it skips the ray test where none can and the tile where all do.
  std::vector<TileCover> bodies;
  std::vector<std::uint32_t> all_tiles;  // every list below, one after the other
  struct ShellLists {
    std::vector<std::pair<TileVariant, TileList>> one_pass;  // by variant (TileVariant::key order)
    TileList gbuffer;
    std::size_t tiles = 0;           // tiles the shell can touch
    std::size_t sky_view_tiles = 0;  // of those, one-pass tiles read from its sky-view table
    std::size_t gbuffer_tiles = 0;   // of those, tiles of the G-buffer path
  };
  std::vector<ShellLists> lists;  // per shell (TileScene::shells)
  std::size_t one_pass_atmosphere_tiles = 0;
  TileList gbuffer_tiles;                                        // tiles of the G-buffer path
  std::vector<std::pair<std::size_t, TileList>> one_body_tiles;  // tiles only body b can be in
  std::size_t one_body_count = 0;
  TileList body_tiles, sun_tiles;  // tiles with several bodies; tiles with the sun only
  /// Tiles drawn by direct_light.comp, and tiles with nothing to draw.
  std::size_t direct_tiles() const { return one_body_count + body_tiles.count + sun_tiles.count; }
  std::size_t black_tiles() const { return tiles - (gbuffer_tiles.count + one_pass_atmosphere_tiles + direct_tiles()); }
};

/// The band of `rows` rows from `first_row` (a multiple of kTileSize) sorted
/// as above.
BandTiles classify_band_tiles(const TileScene& frame, int first_row, int rows);

/// Bodies other than the shell's planet that reach into the shell: their tiles
/// need the aerial perspective the sky-view variant has not.
std::vector<std::size_t> bodies_inside_shell(const scene::Scene& scene, const ShellInView& shell);

}  // namespace zenith::render
