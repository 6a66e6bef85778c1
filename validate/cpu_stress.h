#pragma once
// The CPU path of the numerical-stability stress: the lookup-table queries
// (atmosphere/lut/lookup_tables.h) at the sampler's configurations. No GL.
//
// Per configuration:
//  * sky radiance L = TableQueries::sky_radiance(camera, view, sun) — cameras
//    outside the atmosphere look from where the ray enters it;
//  * transmittance along the view ray through the atmosphere,
//    TableQueries::transmittance from the ray's entry point (found on the
//    perigee form of atmosphere/reference/geometry.h) over its length in the
//    shell — must also be ≤ 1;
//  * irradiance (direct + sky) on a horizontal surface at the camera's radius
//    clamped into the shell, for the sun's cosine there;
//  * for horizon pairs, L at δ = ±ε and the relative jump
//      J = max_λ |L(+ε) − L(−ε)| / max(L(+ε), L(−ε), floor).
//    Across the horizon the radiance changes physically (above it the ray
//    crosses the whole limb, below it ends on the ground), so J is bounded,
//    not zero; a seam between the table halves for rays that hit the ground
//    and rays that do not, or a misclassified ray, shows up as J far above
//    its neighbours'. Measured for cameras inside the atmosphere only.
// Every value is checked for NaN, ±Inf and negative (ValueHealth).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "atmosphere/lut/lookup_tables.h"
#include "validate/stress_sampler.h"
#include "validate/stress_statistics.h"

namespace zenith::validate {

struct CpuStressOptions {
  std::size_t random_samples = 0;  ///< after the sweep
  bool sweep = true;               ///< run StressSampler::sweep() first
  std::uint64_t seed = 1;
  std::uint64_t stream = 0;  ///< distinguishes the models of one run
  double floor_sr = 1e-6;    ///< absolute floor of relative differences [sr^-1 per unit solar irradiance]
  unsigned threads = 0;      ///< 0: all cores
  /// Called with the number of configurations done so far (from worker threads, serialized).
  std::function<void(std::size_t done)> progress;
};

struct CpuStressResult {
  RegionTable regions;
  std::size_t samples = 0;  ///< configurations (sweep + random)
};

/// Evaluates one configuration into `into` (the statistics of its region);
/// `label` names the model in the horizon-jump location.
void evaluate_configuration(const atmosphere::lut::TableQueries& queries, const StressSample& sample, double floor_sr,
                            const std::string& label, RegionStatistics& into);

CpuStressResult run_cpu_stress(const atmosphere::lut::TableQueries& queries, const std::string& label,
                               const CpuStressOptions& options);

}  // namespace zenith::validate
