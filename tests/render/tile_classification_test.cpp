// The sorting of a band's tiles by the pass that draws them
// (render/frame/tile_classification.h), the CPU decisions that pick a frame's
// program variants (render/frame/frame_conditions.h) and the albedo layers
// (render/frame/albedo_layers.h): no GL context, plain scenes and projections.
#include "render/frame/tile_classification.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <vector>

#include <glm/geometric.hpp>

#include "core/units.h"
#include "render/frame/albedo_layers.h"
#include "render/frame/frame_conditions.h"
#include "render/frame/frame_tiles.h"
#include "render/frame/tile_culling.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"

namespace zenith::render {
namespace {

constexpr double kGround = 6.36e6, kTop = 6.42e6;

scene::Body body(const char* name, glm::dvec3 position_m, double radius_m) {
  scene::Body b;
  b.name = name;
  b.position_m = position_m;
  b.radius_m = radius_m;
  return b;
}

/// The camera at the origin looking along −z (camera frame = world frame).
struct View {
  warp::PlanarProjection projection = warp::PlanarProjection::symmetric(256, 192, 60.0);
  TileCones cones{projection};
  scene::Scene scene;
  TileScene tiles;

  View() {
    tiles.scene = &scene;
    tiles.cones = &cones;
    tiles.sun_camera = glm::normalize(glm::dvec3(0.0, 0.0, 1.0));  // behind the camera: no sun tiles
    tiles.sun_reach_rad = 0.01;
  }
  /// A shell around body b of the scene.
  void add_shell(int b, bool drawn = true, bool sky_view = false) {
    const glm::dvec3 c = scene.bodies[static_cast<std::size_t>(b)].position_m;
    tiles.shells.push_back({b, glm::normalize(c), glm::length(c), kTop, drawn, sky_view});
  }
  std::vector<std::uint32_t> touching(std::size_t b, double radius_m) const {
    const glm::dvec3 c = scene.bodies[b].position_m;
    return cones.tiles_touching_sphere(glm::normalize(c), glm::length(c), radius_m, 0, projection.height());
  }
};

std::vector<std::uint32_t> words(const BandTiles& band, TileList list) {
  return {band.all_tiles.begin() + static_cast<std::ptrdiff_t>(list.offset),
          band.all_tiles.begin() + static_cast<std::ptrdiff_t>(list.offset + list.count)};
}

/// How many of the band's drawing lists (one-pass, G-buffer path, direct) hold each tile.
std::map<std::uint32_t, int> times_drawn(const BandTiles& band) {
  std::map<std::uint32_t, int> n;
  auto count = [&](TileList l) {
    for (std::uint32_t t : words(band, l)) ++n[t];
  };
  for (const auto& shell : band.lists)
    for (const auto& [variant, list] : shell.one_pass) count(list);
  count(band.gbuffer_tiles);
  for (const auto& [b, list] : band.one_body_tiles) count(list);
  count(band.body_tiles);
  count(band.sun_tiles);
  return n;
}

void expect_each_tile_drawn_once_or_black(const BandTiles& band, int columns) {
  const std::map<std::uint32_t, int> drawn = times_drawn(band);
  for (const auto& [t, n] : drawn) EXPECT_EQ(n, 1) << "tile " << tile_column(t) << ", " << tile_band_row(t);
  ASSERT_EQ(band.black.size(), band.tiles);
  std::size_t black = 0;
  for (std::size_t i = 0; i < band.tiles; ++i) {
    const std::uint32_t t = pack_tile(static_cast<std::uint32_t>(i % static_cast<std::size_t>(columns)),
                                      static_cast<std::uint32_t>(i / static_cast<std::size_t>(columns)));
    EXPECT_EQ(band.black[i] != 0, !drawn.contains(t)) << "tile " << i;
    black += band.black[i];
  }
  EXPECT_EQ(black, band.black_tiles());
  EXPECT_EQ(drawn.size() + black, band.tiles);
}

TEST(TileClassification, OneShellIsDrawnInOnePassAndAMoonOutsideItDirectly) {
  View v;
  v.scene.bodies = {body("planet", {0, 0, -3e7}, kGround), body("moon", {1.2e7, 0, -3e7}, 1.7e6)};
  v.add_shell(0);
  const BandTiles band = classify_band_tiles(v.tiles, 0, v.projection.height());
  EXPECT_EQ(band.tiles, static_cast<std::size_t>(v.cones.columns() * v.cones.rows()));
  expect_each_tile_drawn_once_or_black(band, v.cones.columns());

  const std::vector<std::uint32_t> shell = v.touching(0, kTop);
  ASSERT_FALSE(shell.empty());
  ASSERT_EQ(band.lists.size(), 1u);
  EXPECT_EQ(band.lists[0].tiles, shell.size());
  EXPECT_EQ(band.lists[0].gbuffer_tiles, 0u) << "one shell: nothing to composite";
  EXPECT_EQ(band.gbuffer_tiles.count, 0u);
  EXPECT_EQ(band.one_pass_atmosphere_tiles, shell.size());
  // The tile at the planet's centre (the image centre) sees ground only; the
  // moon lies beyond the shell (level 1) where its tiles meet the shell's.
  const std::set<std::uint32_t> moon_tiles = [&] {
    const std::vector<std::uint32_t> m = v.touching(1, 1.7e6);
    return std::set<std::uint32_t>(m.begin(), m.end());
  }();
  const std::uint32_t centre =
      pack_tile(static_cast<std::uint32_t>(v.cones.columns() / 2), static_cast<std::uint32_t>(v.cones.rows() / 2));
  bool centre_seen = false;
  for (const auto& [variant, list] : band.lists[0].one_pass)
    for (std::uint32_t t : words(band, list)) {
      EXPECT_EQ(variant.others, moon_tiles.contains(t) ? 1 : 0);
      EXPECT_FALSE(variant.sun);
      EXPECT_FALSE(variant.sky_view);
      if (t == centre) {
        centre_seen = true;
        EXPECT_EQ(variant.ground, TileCover::all);
      }
    }
  EXPECT_TRUE(centre_seen);
  // The moon's tiles outside the shell: direct_light.comp's one-body list of body 1.
  std::size_t moon_direct = 0;
  for (std::uint32_t t : moon_tiles) moon_direct += std::find(shell.begin(), shell.end(), t) == shell.end();
  ASSERT_EQ(band.one_body_tiles.size(), 1u);
  EXPECT_EQ(band.one_body_tiles[0].first, 1u);
  EXPECT_EQ(band.one_body_tiles[0].second.count, moon_direct);
  EXPECT_GT(moon_direct, 0u);
  EXPECT_EQ(band.direct_tiles(), moon_direct);
}

/// Whether the camera-frame ray `d` from the origin meets the sphere (double, exact).
bool meets(const scene::Body& b, const glm::dvec3& d) {
  const double q = glm::dot(b.position_m, d), c = glm::dot(b.position_m, b.position_m) - b.radius_m * b.radius_m;
  return q > 0.0 && q * q >= c;
}

TEST(TileClassification, TheBodyCoverIsNoneWhereNoRayMeetsABodyAndAllWhereEveryRayMeetsThePlanet) {
  // The night sky's pass skips the ray test where the cover is none and the
  // floor-only tile where it is all (render/night/star_pass.cpp): both must
  // hold for every pixel's ray. A planet filling the lower part of the view,
  // its shell drawn, and a moon beyond it.
  View v;
  v.scene.bodies = {body("planet", {0, -6.4e6, -2.0e6}, kGround), body("moon", {2.0e6, 1.5e6, -2.0e7}, 1.7e6)};
  v.add_shell(0);
  const BandTiles band = classify_band_tiles(v.tiles, 0, v.projection.height());
  ASSERT_EQ(band.bodies.size(), band.tiles);
  std::map<TileCover, int> tiles_of;
  for (std::size_t i = 0; i < band.tiles; ++i) {
    const int tx = static_cast<int>(i % static_cast<std::size_t>(v.cones.columns()));
    const int ty = static_cast<int>(i / static_cast<std::size_t>(v.cones.columns()));
    ++tiles_of[band.bodies[i]];
    for (int y = ty * kTileSize; y < std::min((ty + 1) * kTileSize, v.projection.height()); ++y)
      for (int x = tx * kTileSize; x < std::min((tx + 1) * kTileSize, v.projection.width()); ++x) {
        const std::optional<glm::dvec3> d = v.projection.ray(x + 0.5, y + 0.5);
        ASSERT_TRUE(d.has_value());
        const bool planet = meets(v.scene.bodies[0], *d), moon = meets(v.scene.bodies[1], *d);
        if (band.bodies[i] == TileCover::none) {
          EXPECT_FALSE(planet || moon) << "pixel " << x << ", " << y;
        } else if (band.bodies[i] == TileCover::all) {
          EXPECT_TRUE(planet) << "pixel " << x << ", " << y;
        }
      }
  }
  // Each kind is there, and the tiles a body's disc only partly fills are few.
  EXPECT_GT(tiles_of[TileCover::none], 30);
  EXPECT_GT(tiles_of[TileCover::all], 30);
  EXPECT_GT(tiles_of[TileCover::some], 0);
  EXPECT_LT(tiles_of[TileCover::some], tiles_of[TileCover::none] + tiles_of[TileCover::all]);
}

TEST(TileClassification, OverlappingShellsGoThroughTheGbufferPathTogether) {
  View v;
  // Two planets, the second farther and to the side: their shells overlap in part of the view.
  v.scene.bodies = {body("near", {-3e6, 0, -4e7}, kGround), body("far", {8e6, 0, -8e7}, kGround)};
  v.add_shell(0);
  v.add_shell(1);
  const BandTiles band = classify_band_tiles(v.tiles, 0, v.projection.height());
  expect_each_tile_drawn_once_or_black(band, v.cones.columns());
  const std::vector<std::uint32_t> a = v.touching(0, kTop), b = v.touching(1, kTop);
  std::set<std::uint32_t> both;
  for (std::uint32_t t : a)
    if (std::find(b.begin(), b.end(), t) != b.end()) both.insert(t);
  ASSERT_FALSE(both.empty());
  ASSERT_LT(both.size(), a.size());
  for (std::size_t s = 0; s < 2; ++s) {
    const std::vector<std::uint32_t> g = words(band, band.lists[s].gbuffer);
    EXPECT_EQ(std::set<std::uint32_t>(g.begin(), g.end()), both) << "shell " << s;
    EXPECT_EQ(band.lists[s].gbuffer_tiles, both.size());
  }
  const std::vector<std::uint32_t> path = words(band, band.gbuffer_tiles);
  EXPECT_EQ(std::set<std::uint32_t>(path.begin(), path.end()), both);
  EXPECT_EQ(band.one_pass_atmosphere_tiles, a.size() + b.size() - 2 * both.size());
}

TEST(TileClassification, WithoutOnePassTilesEveryTileTakesTheGbufferPath) {
  View v;
  v.scene.bodies = {body("planet", {0, 0, -3e7}, kGround), body("moon", {1.2e7, 0, -3e7}, 1.7e6)};
  v.add_shell(0);
  v.tiles.one_pass_tiles = false;
  const BandTiles band = classify_band_tiles(v.tiles, 0, v.projection.height());
  expect_each_tile_drawn_once_or_black(band, v.cones.columns());
  EXPECT_EQ(band.gbuffer_tiles.count, band.tiles);
  EXPECT_EQ(band.lists[0].gbuffer_tiles, v.touching(0, kTop).size());
  EXPECT_EQ(band.one_pass_atmosphere_tiles, 0u);
  EXPECT_EQ(band.direct_tiles(), 0u);
  EXPECT_EQ(band.black_tiles(), 0u);
}

TEST(TileClassification, AShellWithoutTablesLeavesItsPlanetToTheDirectPass) {
  View v;
  v.scene.bodies = {body("planet", {0, 0, -3e7}, kGround)};
  v.add_shell(0, /*drawn=*/false);
  const BandTiles band = classify_band_tiles(v.tiles, 0, v.projection.height());
  expect_each_tile_drawn_once_or_black(band, v.cones.columns());
  EXPECT_EQ(band.lists[0].tiles, 0u);
  EXPECT_EQ(band.one_pass_atmosphere_tiles, 0u);
  ASSERT_EQ(band.one_body_tiles.size(), 1u);
  EXPECT_EQ(band.one_body_tiles[0].second.count, v.touching(0, kGround).size());
}

TEST(TileClassification, TheSkyViewTableIsNotReadWhereABodyInsideTheShellCanBe) {
  View v;
  // The camera 1 km above the ground looking at the horizon; a 100 m balloon
  // 3 km ahead and 500 m above the camera, inside the shell; the sun in view.
  v.scene.bodies = {body("planet", {0, -(kGround + 1e3), 0}, kGround), body("balloon", {0, 500, -3e3}, 100.0)};
  v.add_shell(0, true, /*sky_view=*/true);
  v.tiles.sun_camera = glm::normalize(glm::dvec3(0.2, 0.1, -1.0));
  const BandTiles band = classify_band_tiles(v.tiles, 0, v.projection.height());
  expect_each_tile_drawn_once_or_black(band, v.cones.columns());
  EXPECT_EQ(bodies_inside_shell(v.scene, v.tiles.shells[0]), std::vector<std::size_t>{1});
  const std::vector<std::uint32_t> balloon = v.touching(1, 100.0);
  ASSERT_FALSE(balloon.empty());
  std::size_t sky_view = 0, sun = 0;
  for (const auto& [variant, list] : band.lists[0].one_pass)
    for (std::uint32_t t : words(band, list)) {
      const bool near_balloon = std::find(balloon.begin(), balloon.end(), t) != balloon.end();
      EXPECT_EQ(variant.sky_view, !near_balloon);
      EXPECT_EQ(variant.others, near_balloon ? 2 : 0);
      sky_view += variant.sky_view;
      sun += variant.sun;
    }
  EXPECT_EQ(band.lists[0].sky_view_tiles, band.lists[0].tiles - balloon.size());
  EXPECT_EQ(band.lists[0].tiles, band.tiles) << "the camera is inside the shell: every tile";
  EXPECT_GT(sun, 0u);
}

TEST(TileClassification, BandsSplitTheFrameTileRowByTileRow) {
  View v;
  v.scene.bodies = {body("planet", {0, 0, -3e7}, kGround), body("moon", {1.2e7, 0, -3e7}, 1.7e6)};
  v.add_shell(0);
  const BandTiles whole = classify_band_tiles(v.tiles, 0, v.projection.height());
  std::size_t one_pass = 0, direct = 0, black = 0;
  for (int first = 0; first < v.projection.height(); first += 3 * kTileSize) {
    const BandTiles band = classify_band_tiles(v.tiles, first, std::min(3 * kTileSize, v.projection.height() - first));
    EXPECT_EQ(band.tile_rows, 3);
    one_pass += band.one_pass_atmosphere_tiles;
    direct += band.direct_tiles();
    black += band.black_tiles();
  }
  EXPECT_EQ(one_pass, whole.one_pass_atmosphere_tiles);
  EXPECT_EQ(direct, whole.direct_tiles());
  EXPECT_EQ(black, whole.black_tiles());
}

TEST(FrameTiles, ClassifiesEveryBandAsAloneAndKeepsThemWhileNothingMoves) {
  View v;
  v.scene.bodies = {body("planet", {0, 0, -3e7}, kGround), body("moon", {1.2e7, 0, -3e7}, 1.7e6)};
  v.add_shell(0);
  v.tiles.sun_camera = glm::normalize(glm::dvec3(0.4, 0.25, -1.0));     // in view, off the shell: sun tiles
  const int height = v.projection.height(), band_rows = 5 * kTileSize;  // 192 rows: 80, 80, 32
  FrameTiles frame;
  const std::vector<BandTiles> bands = frame.classify(v.tiles, height, band_rows);
  EXPECT_FALSE(frame.reused());
  ASSERT_EQ(bands.size(), 3u);
  for (std::size_t b = 0; b < bands.size(); ++b) {
    const int first = static_cast<int>(b) * band_rows;
    const BandTiles alone = classify_band_tiles(v.tiles, first, std::min(band_rows, height - first));
    EXPECT_EQ(bands[b].first_row, first);
    EXPECT_EQ(bands[b].all_tiles, alone.all_tiles) << "band " << b;
    EXPECT_EQ(bands[b].black, alone.black) << "band " << b;
    EXPECT_EQ(bands[b].sun_tiles.count, alone.sun_tiles.count) << "band " << b;
  }
  // The same inputs: the same bands, not classified again.
  EXPECT_EQ(&frame.classify(v.tiles, height, band_rows), &frame.classify(v.tiles, height, band_rows));
  EXPECT_TRUE(frame.reused());
  // Anything the tiles depend on moves: classified again.
  const std::size_t sun_tiles = bands[1].sun_tiles.count + bands[0].sun_tiles.count + bands[2].sun_tiles.count;
  v.tiles.sun_camera = glm::normalize(glm::dvec3(-0.4, 0.25, -1.0));
  const std::vector<BandTiles>& moved = frame.classify(v.tiles, height, band_rows);
  EXPECT_FALSE(frame.reused());
  EXPECT_GT(sun_tiles, 0u);
  EXPECT_NE(moved[0].all_tiles, bands[0].all_tiles);
  v.scene.bodies[1].position_m.x += 1.0;  // a metre
  frame.classify(v.tiles, height, band_rows);
  EXPECT_FALSE(frame.reused());
  frame.classify(v.tiles, height, 6 * kTileSize);  // another band layout
  EXPECT_FALSE(frame.reused());
  frame.forget();  // new tile cones
  frame.classify(v.tiles, height, 6 * kTileSize);
  EXPECT_FALSE(frame.reused());
}

/// sphere_cover tile by tile, as it was before the blocks: the reference the
/// block hierarchy must reproduce exactly.
std::vector<TileCover> cover_tile_by_tile(const TileCones& cones, const glm::dvec3& direction, double distance_m,
                                          double radius_m, int first_tile_row, int tile_rows) {
  std::vector<TileCover> out(static_cast<std::size_t>(tile_rows) * cones.columns(), TileCover::none);
  const bool inside = distance_m <= radius_m;
  const double angular_radius = inside ? 4.0 : std::asin(radius_m / distance_m);
  const glm::dvec3 c = glm::normalize(direction);
  for (int ty = first_tile_row; ty < first_tile_row + tile_rows; ++ty)
    for (int tx = 0; tx < cones.columns(); ++tx) {
      const TileCone& cone = cones.cone(tx, ty);
      if (!cone.has_rays) continue;
      TileCover& cover = out[static_cast<std::size_t>(ty - first_tile_row) * cones.columns() + tx];
      if (inside) {
        cover = TileCover::all;
        continue;
      }
      const double angle = angle_between_units(glm::dvec3(cone.axis), c);
      if (angle > cone.half_angle_rad + angular_radius + 1e-4) continue;
      cover = angle + cone.half_angle_rad + 1e-4 <= angular_radius ? TileCover::all : TileCover::some;
    }
  return out;
}

TEST(TileCulling, BlocksOfTilesGiveExactlyTheTileByTileCover) {
  // Planar views, a 180° dome master and a 360° fisheye (whose rim tiles see
  // everything), spheres from a pixel to most of the sky, near the limb of
  // blocks and tiles, in whole frames and in bands that cut blocks.
  const warp::PlanarProjection planar = warp::PlanarProjection::symmetric(1000, 600, 79.0);
  warp::FisheyeParameters dome;
  const warp::FisheyeProjection fisheye(704, 704, dome);
  warp::FisheyeParameters all_round;
  all_round.fov_deg = 360.0;
  const warp::FisheyeProjection fisheye_360(400, 400, all_round);
  std::mt19937 random(26);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), log_size(-4.0, 0.0);
  std::size_t spheres = 0, all = 0, some = 0;
  for (const warp::Projection* projection :
       std::initializer_list<const warp::Projection*>{&planar, &fisheye, &fisheye_360}) {
    const TileCones cones(*projection);
    for (int n = 0; n < 300; ++n) {
      glm::dvec3 direction(unit(random), unit(random), unit(random) - 0.8);  // mostly in front
      if (glm::length(direction) < 1e-3) continue;
      direction = glm::normalize(direction);
      const double distance_m = 1e7;
      // Angular radii from 1e-4 rad to a hemisphere; one sphere in 20 holds the camera.
      const double radius_m = n % 20 == 0 ? 2e7 : distance_m * std::pow(10.0, log_size(random));
      const int first_tile_row = n % 3 == 0 ? 0 : static_cast<int>(random() % static_cast<unsigned>(cones.rows()));
      const int tile_rows = n % 3 == 0 ? cones.rows() : 1 + static_cast<int>(random() % 11u);
      const int rows_px = std::min(tile_rows * kTileSize, projection->height() - first_tile_row * kTileSize);
      const std::vector<TileCover> blocks =
          cones.sphere_cover(direction, distance_m, radius_m, first_tile_row * kTileSize, rows_px);
      const int band_tile_rows = (rows_px + kTileSize - 1) / kTileSize;
      const std::vector<TileCover> tiles =
          cover_tile_by_tile(cones, direction, distance_m, radius_m, first_tile_row, band_tile_rows);
      ASSERT_EQ(blocks.size(), tiles.size());
      for (std::size_t i = 0; i < tiles.size(); ++i) {
        ASSERT_EQ(blocks[i], tiles[i]) << projection->describe() << ", sphere " << n << ", tile " << i;
        all += tiles[i] == TileCover::all;
        some += tiles[i] == TileCover::some;
      }
      ++spheres;
    }
  }
  EXPECT_GT(spheres, 800u);
  EXPECT_GT(all, 10000u) << "blocks inside the disc decided whole";
  EXPECT_GT(some, 1000u) << "limbs decided tile by tile";
}

TEST(FrameConditions, TheSkyViewTableServesLowCamerasAndDaylightUpToAFifthOfTheShell) {
  const double thickness = kTop - kGround;
  EXPECT_TRUE(sky_view_accurate(kGround + 0.02 * thickness, kGround, kTop, -0.9)) << "2 %: always";
  EXPECT_TRUE(sky_view_accurate(kGround + 0.1 * thickness, kGround, kTop, 0.0));
  // At 10 % the horizon is at μ = −√(1 − (RB/r)²) = −0.0434: a sun just below it is twilight.
  const double r = kGround + 0.1 * thickness;
  const double mu_horizon = -std::sqrt(1.0 - (kGround / r) * (kGround / r));
  EXPECT_TRUE(sky_view_accurate(r, kGround, kTop, mu_horizon + 1e-6));
  EXPECT_FALSE(sky_view_accurate(r, kGround, kTop, mu_horizon - 1e-6));
  EXPECT_FALSE(sky_view_accurate(kGround + 0.25 * thickness, kGround, kTop, 1.0)) << "above 20 %: never";
}

TEST(FrameConditions, EclipsesArePossibleOnlyNearTheShadowAxis) {
  scene::Scene s;
  s.sun.direction = {1, 0, 0};
  s.sun.angular_radius_rad = 0.00465;
  // The moon between the sun and the planet, 0.5 Earth radii off the axis: its penumbra reaches the planet.
  s.bodies = {body("planet", {0, 0, 0}, kGround), body("moon", {3.8e8, 0.5 * kGround, 0}, 1.74e6)};
  EXPECT_TRUE(eclipses_possible(s));
  // 3 Earth radii off the axis: the penumbra (radius a + d tan α ≈ 3.5e6 m) misses the planet, and the
  // planet's shadow points away from the moon.
  s.bodies[1].position_m = {3.8e8, 3.0 * kGround, 0};
  EXPECT_FALSE(eclipses_possible(s));
  // Behind the planet, in its shadow: the planet eclipses the moon.
  s.bodies[1].position_m = {-3.8e8, 0, 0};
  EXPECT_TRUE(eclipses_possible(s));
}

TEST(FrameConditions, AnAirlessBodyShadowsTheAirWhereItsShadowReachesItAndItIsLargeEnough) {
  scene::Scene s;
  s.sun.direction = {1, 0, 0};
  s.sun.angular_radius_rad = 0.00465;
  scene::Body planet = body("planet", {0, 0, 0}, kGround);
  planet.atmosphere.emplace();
  planet.atmosphere->loaded.model.ground_radius_m = kGround;
  planet.atmosphere->loaded.model.top_radius_m = kGround + 100e3;
  // The Moon's distance, 0.5 Earth radii off the axis: its shadow reaches the air.
  s.bodies = {planet, body("moon", {3.8e8, 0.5 * kGround, 0}, 1.74e6)};
  EXPECT_TRUE(shadow_on_air_possible(s, s.bodies[1], s.bodies[0]));
  EXPECT_TRUE(airless_shadow_on_air_possible(s));
  EXPECT_FALSE(shadow_on_air_possible(s, s.bodies[0], s.bodies[1])) << "the receiver has no air";
  // Its penumbra (≈ 3.5e6 m) passes 100 km above the top of the air: out of reach.
  s.bodies[1].position_m = {3.8e8, kGround + 100e3 + 3.6e6, 0};
  EXPECT_FALSE(shadow_on_air_possible(s, s.bodies[1], s.bodies[0]));
  // A spacecraft 50 m in radius 400 km up, on the axis: 1.7e-4 rad in radius seen from the top of the
  // air, under a third of the sun's (its shadow on the ground is the bodies' code's).
  s.bodies[1] = body("spacecraft", {kGround + 400e3, 0, 0}, 50.0);
  EXPECT_FALSE(shadow_on_air_possible(s, s.bodies[1], s.bodies[0]));
  EXPECT_TRUE(eclipses_possible(s));
  // A body in the air itself: not the shadow model's Moon.
  s.bodies[1] = body("balloon", {kGround + 30e3, 0, 0}, 20e3);
  EXPECT_FALSE(shadow_on_air_possible(s, s.bodies[1], s.bodies[0]));
  EXPECT_FALSE(airless_shadow_on_air_possible(s));
}

TEST(FrameConditions, AlbedoAtFullResolutionWhileTwentyPixelFootprintsStayUnderATexel) {
  scene::Scene s;
  s.bodies = {body("moon", {0, 0, -1e8}, 1.74e6)};
  const double farthest = std::sqrt((1e8 - 1.74e6) * (1e8 + 1.74e6));
  const int width = 1024;
  const double texel = 2.0 * core::kPi * 1.74e6 / width;
  const double limit = 0.99 * texel / (20.0 * farthest);  // the largest pixel angle at level 0
  EXPECT_TRUE(albedo_at_full_resolution(s, 0.999 * limit, width));
  EXPECT_FALSE(albedo_at_full_resolution(s, 1.001 * limit, width));
}

TEST(AlbedoLayers, MapsAreResampledToTheLargestSizeWrappingInLongitude) {
  image::LinearImage two, four;
  two.width = 2;
  two.height = 1;
  two.rgb = {0.1f, 0.2f, 0.3f, 0.5f, 0.6f, 0.7f};
  four.width = 4;
  four.height = 2;
  four.rgb.assign(4 * 2 * 3, 0.25f);
  const AlbedoLayers layers = resample_albedo_layers({&two, &four});
  ASSERT_EQ(layers.width, 4);
  ASSERT_EQ(layers.height, 2);
  ASSERT_EQ(layers.layers, 2u);
  ASSERT_EQ(layers.rgba.size(), 2u * 4 * 2 * 4);
  // Texel x of 4 samples the 2-texel map at x' = (x + ½)/2 − ½: −¼, ¼, ¾, 1¼, wrapping.
  const double a[3] = {0.1, 0.2, 0.3}, b[3] = {0.5, 0.6, 0.7};
  const double weight_of_a[4] = {0.75, 0.75, 0.25, 0.25};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      for (int k = 0; k < 3; ++k) {
        const double expected = weight_of_a[x] * a[k] + (1.0 - weight_of_a[x]) * b[k];
        EXPECT_NEAR(layers.rgba[(static_cast<std::size_t>(y) * 4 + x) * 4 + k], expected, 1e-6) << x << ", " << y;
      }
  for (std::size_t i = 0; i < 4 * 2; ++i) {
    EXPECT_EQ(layers.rgba[4 * 2 * 4 + 4 * i], 0.25f) << "a map of the largest size is copied";
    EXPECT_EQ(layers.rgba[4 * i + 3], 1.0f) << "alpha";
  }
  const AlbedoLayers none = resample_albedo_layers({});
  EXPECT_EQ(none.layers, 1u);
  EXPECT_EQ(none.rgba, std::vector<float>(4, 1.0f)) << "no map: one white texel";
}

TEST(AlbedoLayers, AMapOfTheArraysSizeIsCopiedAndAConstantFillsItsLayer) {
  image::LinearImage one, three;
  one.width = one.height = 1;
  one.rgb = {0.28f, 0.17f, 0.07f};
  three.width = 3;
  three.height = 2;
  for (int i = 0; i < 3 * 2 * 3; ++i) three.rgb.push_back(0.01f * static_cast<float>(i * i) + 0.003f);
  const AlbedoLayers layers = resample_albedo_layers({&one, &three});
  ASSERT_EQ(layers.width, 3);
  ASSERT_EQ(layers.height, 2);
  ASSERT_EQ(layers.rgba.size(), 2u * 3 * 2 * 4);
  for (std::size_t t = 0; t < 3 * 2; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(layers.rgba[4 * t + k], one.rgb[k]) << "the constant, texel " << t;
      EXPECT_EQ(layers.rgba[3 * 2 * 4 + 4 * t + k], three.rgb[3 * t + k]) << "the same bits, texel " << t;
      EXPECT_EQ(layers.rgba[3 * 2 * 4 + 4 * t + 3], 1.0f) << "alpha";
    }
}

}  // namespace
}  // namespace zenith::render
