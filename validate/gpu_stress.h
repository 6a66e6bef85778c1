#pragma once
// The GPU path of the numerical-stability stress: small frames of one planet
// rendered by render::Renderer (shaders, float) at the hard corners, checked
// pixel by pixel. Needs a current GL context (Mesa llvmpipe without a GPU).
//
// Cases, per model: camera altitude {1 m, half the atmosphere, 1000 km above
// the top, 40 au} × sun zenith {30°, 89.5°, 96°, 104°, 150°} × two views:
//  * "horizon": a planar 4×64 frustum centred on the geometric horizon (the
//    limb, from space), 90° in azimuth from the sun, half-height 0.5° (from
//    space: a quarter of the planet's angular radius, ≥ 2e-7 rad at 40 au);
//  * "wide": inside the atmosphere a 64×64 fisheye of 220° looking along the
//    horizon; from space a 64×64 planar frame 1.5 planet radii across, centred
//    on the planet.
// Per frame: NaN/Inf/negative pixel values (all three channels, sun disc
// drawn); in the horizon frame the largest relative step between consecutive
// rows of the centre column, |a − b| / max(a, b, floor) (the geometric horizon
// lies between two rows: a physical step, bounded; cameras inside the
// atmosphere only, from space the frame's top is black space), and for pixels whose ray
// misses the ground and lies more than max(1°, 3 pixels) from the sun, the relative
// difference to the CPU table query of the same ray (float vs double, same tables).
#include <string>
#include <vector>

#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/parameters.h"
#include "render/renderer.h"

namespace zenith::validate {

struct GpuFrameResult {
  std::string model, view;
  double altitude_m = 0.0, sun_zenith_deg = 0.0;
  std::size_t values = 0, nan = 0, inf = 0, negative = 0;
  double max_row_jump = 0.0;        ///< horizon view: largest step between consecutive rows (relative)
  int max_row_jump_row = -1;        ///< the lower row of that step
  double max_cpu_difference = 0.0;  ///< largest relative difference to the CPU query (sky pixels)
  std::size_t compared = 0;         ///< pixels compared with the CPU
  double seconds = 0.0;
  std::size_t bad() const { return nan + inf + negative; }
};

struct GpuStressOptions {
  double floor_sr = 1e-6;  ///< per unit solar irradiance; scaled by the sun's irradiance for pixels
  int size_px = 64;
};

/// Renders every case for one atmosphere. `renderer` must obtain the tables
/// of `atmosphere.model` (the same set `queries` reads) through its TableSource.
std::vector<GpuFrameResult> run_gpu_stress(render::Renderer& renderer, const std::string& label,
                                           const atmosphere::LoadedAtmosphere& atmosphere,
                                           const atmosphere::lut::TableQueries& queries,
                                           const GpuStressOptions& options);

}  // namespace zenith::validate
