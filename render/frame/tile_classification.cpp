#include "render/frame/tile_classification.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

namespace zenith::render {

int TileVariant::key() const {
  return (sky_view ? 1 : 0) | static_cast<int>(ground) << 1 | others << 3 | (sun ? 1 : 0) << 5;
}

TileVariant general_tile_variant(TileVariant v) {
  v.ground = TileCover::some;
  return v;
}

std::vector<std::size_t> bodies_inside_shell(const scene::Scene& scene, const ShellInView& shell) {
  std::vector<std::size_t> inside;
  const glm::dvec3 centre = scene.bodies[static_cast<std::size_t>(shell.body)].position_m;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (static_cast<int>(b) != shell.body &&
        glm::length(scene.bodies[b].position_m - centre) - scene.bodies[b].radius_m < shell.top_radius_m)
      inside.push_back(b);
  return inside;
}

BandTiles classify_band_tiles(const TileScene& frame, int first_row, int rows) {
  const scene::Scene& scene = *frame.scene;
  const TileCones& cones = *frame.cones;
  const std::vector<ShellInView>& passes = frame.shells;
  BandTiles band;
  band.first_row = first_row;
  band.rows = rows;
  band.tile_rows = (rows + kTileSize - 1) / kTileSize;
  band.tiles = static_cast<std::size_t>(cones.columns()) * band.tile_rows;
  const std::size_t band_tiles = band.tiles;
  auto tile_index = [&](std::uint32_t t) {
    return tile_band_row(t) * static_cast<std::size_t>(cones.columns()) + tile_column(t);
  };
  auto body_touches = [&](std::size_t b) {
    const glm::dvec3 c = scene.bodies[b].position_m - scene.camera.position_m;
    return cones.tiles_touching_sphere(frame.world_to_camera * glm::normalize(c), glm::length(c),
                                       scene.bodies[b].radius_m, first_row, rows);
  };
  // Per shell: the band's tiles it can touch; of those, the tiles no other
  // shell touches, drawn in one pass by variant (TileVariant::key), and the
  // others, which go through the G-buffer path.
  struct ShellTiles {
    std::vector<std::uint32_t> shell_tiles, gbuffer_tiles;
    // Indexed by TileVariant::key() (under kVariantKeys): a table, not a map, since
    // every tile of the shell is filed here (262 144 on an 8192² dome master).
    std::array<std::vector<std::uint32_t>, kVariantKeys> one_pass;
    std::array<TileVariant, kVariantKeys> variants;
  };
  std::vector<ShellTiles> shell_lists(passes.size());
  std::vector<std::uint8_t>& shells = band.shells;
  shells.assign(band_tiles, 0);
  for (std::size_t a = 0; a < passes.size(); ++a) {
    const ShellInView& pass = passes[a];
    ShellTiles& lists = shell_lists[a];
    lists.shell_tiles = pass.drawn ? cones.tiles_touching_sphere(pass.direction_camera, pass.distance_m,
                                                                 pass.top_radius_m, first_row, rows)
                                   : std::vector<std::uint32_t>{};
    for (std::uint32_t t : lists.shell_tiles)
      shells[tile_index(t)] = static_cast<std::uint8_t>(std::min(shells[tile_index(t)] + 1, 2));
  }
  enum TileUse : std::uint8_t { kGbuffer = 1, kBody = 2, kSun = 4 };
  std::vector<std::uint8_t> use(band_tiles, 0);
  auto mark = [&](const std::vector<std::uint32_t>& list, std::uint8_t flag) {
    for (std::uint32_t t : list) use[tile_index(t)] |= flag;
  };
  // Per body, the tiles it can be in (for the one-pass variants and the direct tiles).
  std::vector<std::vector<std::uint32_t>> body_tiles_of(scene.bodies.size());
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    body_tiles_of[b] = body_touches(b);
    mark(body_tiles_of[b], kBody);
  }
  band.bodies.assign(band_tiles, TileCover::some);
  for (std::size_t i = 0; i < band_tiles; ++i)
    if ((use[i] & kBody) == 0) band.bodies[i] = TileCover::none;
  if (frame.sun_disc)
    mark(cones.tiles_touching_sphere(frame.sun_camera, 1.0, std::sin(frame.sun_reach_rad), first_row, rows), kSun);
  for (std::size_t a = 0; a < passes.size(); ++a) {
    const ShellInView& pass = passes[a];
    ShellTiles& lists = shell_lists[a];
    if (lists.shell_tiles.empty()) continue;
    const scene::Body& planet = scene.bodies[static_cast<std::size_t>(pass.body)];
    const glm::dvec3 to_planet = planet.position_m - scene.camera.position_m;
    const std::vector<TileCover> ground = cones.sphere_cover(frame.world_to_camera * glm::normalize(to_planet),
                                                             glm::length(to_planet), planet.radius_m, first_row, rows);
    // Other bodies: 1 where one beyond the shell can be, 2 where one inside it can be.
    std::vector<std::uint8_t> others(band_tiles, 0);
    const std::vector<std::size_t> inside = bodies_inside_shell(scene, pass);
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      if (static_cast<int>(b) == pass.body) continue;
      const std::uint8_t level = std::find(inside.begin(), inside.end(), b) != inside.end() ? 2 : 1;
      for (std::uint32_t t : body_tiles_of[b]) others[tile_index(t)] = std::max(others[tile_index(t)], level);
    }
    for (std::uint32_t t : lists.shell_tiles) {
      const std::size_t i = tile_index(t);
      if (ground[i] == TileCover::all) band.bodies[i] = TileCover::all;
      if (shells[i] > 1 || !frame.one_pass_tiles) {
        lists.gbuffer_tiles.push_back(t);
        continue;
      }
      TileVariant v;
      v.sky_view = pass.sky_view && others[i] < 2;
      v.ground = ground[i];
      v.others = others[i];
      v.sun = (use[i] & kSun) != 0;
      const int key = v.key();
      lists.variants[static_cast<std::size_t>(key)] = v;
      lists.one_pass[static_cast<std::size_t>(key)].push_back(t);
    }
    mark(lists.gbuffer_tiles, kGbuffer);
  }
  if (!frame.one_pass_tiles)
    mark(cones.tiles_touching_sphere(glm::dvec3(0, 0, -1), 0.0, 1.0, first_row, rows), kGbuffer);
  // One buffer per band holds every list: each atmosphere's, then the
  // G-buffer path's tiles, the bodies' and the sun's direct tiles.
  std::vector<std::uint32_t>& all_tiles = band.all_tiles;
  auto append = [&](const std::vector<std::uint32_t>& list) {
    const TileList l{all_tiles.size(), list.size()};
    all_tiles.insert(all_tiles.end(), list.begin(), list.end());
    return l;
  };
  band.lists.resize(passes.size());
  for (std::size_t a = 0; a < passes.size(); ++a) {
    const ShellTiles& pass = shell_lists[a];
    BandTiles::ShellLists& st = band.lists[a];
    for (std::size_t key = 0; key < kVariantKeys; ++key) {
      const std::vector<std::uint32_t>& list = pass.one_pass[key];
      if (list.empty()) continue;
      const TileVariant& v = pass.variants[key];
      st.one_pass.emplace_back(v, append(list));
      band.one_pass_atmosphere_tiles += list.size();
      if (v.sky_view) st.sky_view_tiles += list.size();
    }
    st.gbuffer = append(pass.gbuffer_tiles);
    st.tiles = pass.shell_tiles.size();
    st.gbuffer_tiles = pass.gbuffer_tiles.size();
  }
  auto list_where = [&](auto&& keep) {  // the band's tiles i with keep(i), row by row
    TileList l{all_tiles.size(), 0};
    for (std::size_t i = 0; i < band_tiles; ++i)
      if (keep(i)) {
        all_tiles.push_back(pack_tile(static_cast<std::uint32_t>(i % static_cast<std::size_t>(cones.columns())),
                                      static_cast<std::uint32_t>(i / static_cast<std::size_t>(cones.columns()))));
        ++l.count;
      }
    return l;
  };
  band.gbuffer_tiles = list_where([&](std::size_t i) { return (use[i] & kGbuffer) != 0; });
  // Body tiles (no shell, no sun): those only one body can be in, per body
  // (direct_light.comp's ONE_BODY, its data as uniforms), then the others.
  std::vector<std::uint8_t> body_count(band_tiles, 0);
  for (const auto& list : body_tiles_of)
    for (std::uint32_t t : list)
      body_count[tile_index(t)] = static_cast<std::uint8_t>(std::min(body_count[tile_index(t)] + 1, 2));
  auto body_only = [&](std::size_t i) { return shells[i] == 0 && use[i] == kBody; };
  for (std::size_t b = 0; b < body_tiles_of.size(); ++b) {
    std::vector<std::uint32_t> only;
    for (std::uint32_t t : body_tiles_of[b])
      if (body_only(tile_index(t)) && body_count[tile_index(t)] == 1) only.push_back(t);
    if (only.empty()) continue;
    band.one_body_tiles.emplace_back(b, append(only));
    band.one_body_count += only.size();
  }
  band.body_tiles = list_where([&](std::size_t i) { return body_only(i) && body_count[i] > 1; });
  band.sun_tiles =
      list_where([&](std::size_t i) { return shells[i] == 0 && (use[i] & kGbuffer) == 0 && (use[i] & kSun) != 0; });
  // Tiles nothing is dispatched for stay black: not cleared on the GPU, zeros in the rows.
  band.black.assign(band_tiles, 0);
  for (std::size_t i = 0; i < band_tiles; ++i) band.black[i] = shells[i] == 0 && use[i] == 0;
  return band;
}

}  // namespace zenith::render
