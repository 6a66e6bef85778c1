#pragma once
// Output of `zenith validate stress`: CSV files and the table printed on
// stdout (docs/validation.md "Numerical stability" shows and explains them).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "validate/gpu_stress.h"
#include "validate/stress_statistics.h"

namespace zenith::validate {

/// The CPU results of one model.
struct ModelResult {
  std::string model;
  RegionTable regions;
  double cpu_seconds = 0.0, reference_seconds = 0.0;
};

/// stress_regions.csv: one row per (model, region), then model "all" per region
/// and region "all". Columns: model, region, samples, values, nan, inf,
/// negative, transmittance_above_1, max_horizon_jump, reference_samples,
/// reference_median, reference_p95, reference_max, max_horizon_jump_at, reference_max_at.
std::string regions_csv(const std::vector<ModelResult>& models);
/// stress_gpu.csv: one row per rendered frame.
std::string gpu_csv(const std::vector<GpuFrameResult>& frames);
/// The human-readable summary (per region over all models, then the worst places).
std::string summary_table(const std::vector<ModelResult>& models, const std::vector<GpuFrameResult>& frames);

/// All models merged, per region.
RegionTable all_models(const std::vector<ModelResult>& models);

}  // namespace zenith::validate
