#pragma once
// The renderer: scenes of analytic planets with precomputed atmospheres, seen
// through any projection (paper section 5.2, Algorithm 1). Per frame:
//
//   1. body pass (shaders/render/gbuffer.comp): every pixel's ray from the
//      projection, the nearest sphere, its albedo → G-buffer;
//   2. per group of 4 wavelengths:
//      a. one pass per atmosphere, front to back, over the 16×16 tiles its
//         shell can touch (atmosphere_pass.comp): in-scattering, transmittance,
//         the ground of its own planet (paper Algorithm 1);
//      b. resolve (resolve.comp): airless surfaces and the sun's disc behind
//         the atmospheres, then spectral radiance → linear sRGB × exposure;
//   3. read back, hand rows to the caller (EXR/PNG writers stream them).
//
// Large frames are rendered in horizontal bands of at most
// RenderOptions::max_band_pixels so GPU memory stays bounded (8K dome masters).
// Needs a current GL 4.5 context (gl::HeadlessContext or a window).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "atmosphere/lut/lookup_tables.h"
#include "render/frame/gpu_atmosphere.h"
#include "render/image/colour.h"
#include "render/scene/scene.h"
#include "warp/projection.h"

namespace zenith::render {

struct RenderOptions {
  bool atmospheres = true;      ///< false: bodies lit by the sun only (the benchmarks' baseline)
  bool sun_disc = true;         ///< draw the sun's disc
  bool limb_darkening = true;   ///< darken the disc toward its limb (off: uniform disc)
  AtmospherePassFeatures atmosphere;  ///< multiple scattering, eclipses, shader precision
  image::ColourMapping colour = image::ColourMapping::automatic;
  /// Pixels per band; the frame is split into bands of whole 16-pixel tile rows.
  std::size_t max_band_pixels = std::size_t{4} << 20;
};

/// Tables for an atmosphere model (e.g. from the cache, else precomputed):
/// called only for table sets the renderer does not hold yet.
using TableSource = std::function<atmosphere::lut::LookupTables(const atmosphere::AtmosphereModel&)>;

/// Receives finished rows, top first: `row_count` rows from `first_row`, linear
/// sRGB radiance × exposure, 3 floats per pixel, x fastest.
using RowSink = std::function<void(int first_row, int row_count, std::span<const float> rgb)>;

/// What the last frame did, for logs, tests and benchmarks.
struct FrameStats {
  struct Atmosphere {
    std::string body;
    std::size_t tiles = 0;        ///< tiles its pass covered (all bands)
    std::size_t tiles_total = 0;  ///< tiles in the frame
  };
  std::vector<Atmosphere> atmospheres;  ///< in the order the passes ran
  int table_sets_requested = 0;         ///< TableSource calls during the frame
  int table_sets_uploaded = 0;
  int bands = 0;
  double seconds = 0.0;                 ///< wall time of render(), readback included
};

class Renderer {
 public:
  Renderer(const RenderOptions& options, TableSource tables);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renders `scene` through `projection` (its camera, sun and bodies), handing
  /// rows to `sink` as bands finish. Throws std::invalid_argument for scenes it
  /// cannot render (more than 64 bodies, an atmosphere at other wavelengths than
  /// the scene's) and std::runtime_error for GL failures.
  void render(const scene::Scene& scene, const warp::Projection& projection, const RowSink& sink);
  /// The whole frame in memory: width · height · 3 floats.
  std::vector<float> render_image(const scene::Scene& scene, const warp::Projection& projection);

  const FrameStats& last_frame() const { return stats_; }
  const RenderOptions& options() const { return options_; }

 private:
  struct Impl;
  RenderOptions options_;
  TableSource table_source_;
  std::unique_ptr<Impl> impl_;
  FrameStats stats_;
};

}  // namespace zenith::render
