#pragma once
// Every band's tile classification of a frame (render/frame/tile_classification.h),
// done before the first band is drawn: the bands at once on the CPU's cores,
// and not at all while nothing it depends on has changed since the last frame.
//
// The classification is the CPU's share of a frame on a GPU: on an H100 it was
// about half of a live 3840×2160 ground-view frame and of an 8192² dome
// master with three atmospheres, with the GPU waiting. A node's
// frames of a still scene (a paused show, a fade, a slide) classify once; a
// moving camera, sun or body classifies every frame, band by band in parallel.
#include <vector>

#include "render/frame/tile_classification.h"

namespace zenith::render {

class FrameTiles {
 public:
  /// The bands of rows [0, height) in steps of `band_rows` (a multiple of
  /// kTileSize), classified against `tiles`, or the last call's bands when
  /// every input of the classification is the same bit for bit (the scene's
  /// bodies and camera, the shells, the sun, the options, the band layout)
  /// and forget() was not called since.
  const std::vector<BandTiles>& classify(const TileScene& tiles, int height, int band_rows);
  /// Whether the last classify() handed back the bands before it.
  bool reused() const { return reused_; }
  /// Drops the bands kept (the projection's tile cones changed).
  void forget();

 private:
  std::vector<double> key_;  // every number the classification reads, in a fixed order
  std::vector<BandTiles> bands_;
  bool reused_ = false;
};

}  // namespace zenith::render
