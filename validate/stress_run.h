#pragma once
// `zenith validate stress` (docs/validation.md "Numerical stability"): the
// numerically hard corners — cameras from 1 m to 40 au, views on and within
// 1e-6 rad of the horizon, the sun through twilight and night, every preset
// and random parameter sets — on the CPU path (table queries, with single
// scattering checked against the exact quadrature per region) and the GPU path
// (rendered frames). Writes stress_regions.csv and stress_gpu.csv, prints a
// table, and fails (exit 1) on any NaN, Inf, negative value or transmittance
// above 1, or on a --bound exceeded.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "validate/validation_tables.h"

namespace zenith::validate {

struct StressOptions {
  std::size_t samples = 1000000;       ///< CPU configurations in all (split over the models), after the sweep
  std::uint64_t seed = 1;              ///< the samples and the random parameter sets
  std::vector<std::string> presets;    ///< empty: every preset
  std::size_t random_models = 2;       ///< random parameter sets besides the presets
  std::size_t reference_samples = 50;  ///< single-scattering comparisons per region and model
  double floor_sr = 1e-6;              ///< absolute floor of relative errors [sr⁻¹ per unit solar irradiance]
  bool gpu = true;                     ///< also render frames on the GPU path (skipped without a GL context)
  unsigned threads = 0;                ///< CPU threads (0: all)
  std::string out;                     ///< stress_regions.csv and stress_gpu.csv go here ("" none)
  /// "NAME=VALUE": fail when the figure NAME exceeds VALUE; NAME is
  /// <region>.median|p95|max, horizon_jump, gpu_row_jump or gpu_cpu_difference.
  std::vector<std::string> bounds;
};

/// Runs the CPU, reference and GPU paths and prints the table; throws
/// std::runtime_error on any bad value or bound exceeded, std::invalid_argument
/// for a bound that names no figure (before any work).
void validate_stress(const StressOptions& options, const TablesFor& tables_for);

}  // namespace zenith::validate
