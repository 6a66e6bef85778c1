#include "render/frame/frame_tiles.h"

#include <algorithm>

#include "core/parallel_for.h"

namespace zenith::render {
namespace {

/// Every input of classify_band_tiles besides the tile cones, as numbers
/// (flags as 0/1), so that one comparison tells whether a frame's tiles can be
/// those of the frame before.
std::vector<double> classification_key(const TileScene& t, int height, int band_rows) {
  std::vector<double> key = {static_cast<double>(height), static_cast<double>(band_rows), t.sun_reach_rad,
                             t.sun_disc ? 1.0 : 0.0, t.one_pass_tiles ? 1.0 : 0.0};
  auto add = [&](const glm::dvec3& v) { key.insert(key.end(), {v.x, v.y, v.z}); };
  add(t.sun_camera);
  for (int c = 0; c < 3; ++c) add(t.world_to_camera[c]);
  add(t.scene->camera.position_m);
  key.push_back(static_cast<double>(t.scene->bodies.size()));
  for (const scene::Body& b : t.scene->bodies) {
    add(b.position_m);
    key.push_back(b.radius_m);
  }
  key.push_back(static_cast<double>(t.shells.size()));
  for (const ShellInView& s : t.shells) {
    add(s.direction_camera);
    key.insert(key.end(), {static_cast<double>(s.body), s.distance_m, s.top_radius_m, s.drawn ? 1.0 : 0.0,
                           s.sky_view ? 1.0 : 0.0});
  }
  return key;
}

}  // namespace

const std::vector<BandTiles>& FrameTiles::classify(const TileScene& tiles, int height, int band_rows) {
  std::vector<double> key = classification_key(tiles, height, band_rows);
  reused_ = !bands_.empty() && key == key_;
  if (reused_) return bands_;
  const std::size_t count = static_cast<std::size_t>((height + band_rows - 1) / band_rows);
  std::vector<BandTiles> bands(count);
  // Each band on its own core: classify_band_tiles reads only its arguments.
  core::parallel_for(count, 0, [&](std::size_t b) {
    const int first_row = static_cast<int>(b) * band_rows;
    bands[b] = classify_band_tiles(tiles, first_row, std::min(band_rows, height - first_row));
  });
  bands_ = std::move(bands);
  key_ = std::move(key);
  return bands_;
}

void FrameTiles::forget() {
  bands_.clear();
  key_.clear();
  reused_ = false;
}

}  // namespace zenith::render
