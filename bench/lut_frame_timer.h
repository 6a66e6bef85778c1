#pragma once
// Frame time of the renderer with given sets of lookup tables, at a fixed
// size: a square fisheye dome master (180°) of a scene with one atmosphere
// (configs/scenes/earth-ground-noon.json, mars-ground-day.json), for the
// "run time against error" benchmark (bench/lut_accuracy_bench.cpp).
//
// The scene's bodies get a constant albedo (no albedo map to generate: the
// frame measures the passes, not the set-up). Each set of tables gets a
// render::Renderer of its own and one untimed frame when added (table upload,
// tile cones, shader compilation; its pixels are checked for NaN/Inf). The
// timed frames (wall clock around Renderer::render(), readback included) run
// round by round over all the sets, so that a burst of load from other
// processes spreads over them instead of spoiling one. Needs a current GL 4.5
// context (render::gl::HeadlessContext).
#include <cstddef>
#include <filesystem>
#include <memory>
#include <vector>

#include "atmosphere/lut/lookup_tables.h"
#include "scene/scene.h"

namespace zenith::render {
class Renderer;
}
namespace zenith::warp {
class FisheyeProjection;
}

namespace zenith::bench {

struct FrameTiming {
  double median_ms = 0.0;
  double min_ms = 0.0;
  int frames = 0;
  std::size_t nonfinite_values = 0;  ///< NaN or ±Inf in the untimed frame's RGB values
};

class LutFrameTimer {
 public:
  /// Reads the scene; it must have exactly one atmosphere. Throws on errors.
  LutFrameTimer(const std::filesystem::path& scene_file, int size_px);
  ~LutFrameTimer();
  LutFrameTimer(const LutFrameTimer&) = delete;
  LutFrameTimer& operator=(const LutFrameTimer&) = delete;

  /// The scene's atmosphere model: the tables handed to add() must be its.
  const atmosphere::AtmosphereModel& model() const;
  int size_px() const { return size_px_; }

  /// Takes a set of tables (computed for model()), renders its untimed frame;
  /// returns its index and the non-finite values of that frame.
  std::size_t add(atmosphere::lut::LookupTables tables, std::size_t* nonfinite_values = nullptr);

  /// `frames` timed frames of every set added, interleaved; index as add().
  std::vector<FrameTiming> time_all(int frames);

 private:
  struct Entry;
  scene::Scene scene_;
  int size_px_ = 512;
  std::unique_ptr<warp::FisheyeProjection> projection_;  ///< one object: renderers keep per-projection state
  std::vector<std::unique_ptr<Entry>> entries_;
};

}  // namespace zenith::bench
