#include "validate/stress_run.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "atmosphere/model_hash.h"
#include "atmosphere/named_inputs.h"
#include "atmosphere/parameters.h"
#include "core/parallel_for.h"
#include "core/progress_bar.h"
#include "core/strings.h"
#include "core/timing.h"
#include "render/gl/egl_context.h"
#include "render/renderer.h"
#include "validate/cpu_stress.h"
#include "validate/gpu_stress.h"
#include "validate/random_atmosphere.h"
#include "validate/reference_comparison.h"
#include "validate/stress_report.h"

namespace zenith::validate {
namespace {

struct StressModel {
  std::string label;
  atmosphere::LoadedAtmosphere loaded;
  atmosphere::lut::LookupTables tables;
};

using core::seconds_since;

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  if (!f) throw std::runtime_error(core::cat("cannot write ", path.string()));
}

/// The measured value a --bound names: "<region>.median|p95|max" (single-scattering
/// error over all models), "horizon_jump" (CPU, all regions), "gpu_row_jump",
/// "gpu_cpu_difference" (largest over the frames).
double bounded_value(const std::string& name, const RegionTable& all, const std::vector<GpuFrameResult>& frames) {
  if (name == "horizon_jump") return total(all).horizon_jump.value;
  if (name == "gpu_row_jump" || name == "gpu_cpu_difference") {
    double v = 0.0;
    for (const auto& f : frames) v = std::max(v, name == "gpu_row_jump" ? f.max_row_jump : f.max_cpu_difference);
    return v;
  }
  const std::size_t dot = name.find('.');
  for (Region r : kRegions)
    if (dot != std::string::npos && name.substr(0, dot) == region_name(r)) {
      const ErrorDistribution& e = all[std::size_t(r)].reference;
      const std::string stat = name.substr(dot + 1);
      if (stat == "median") return e.median();
      if (stat == "p95") return e.quantile(0.95);
      if (stat == "max") return e.max();
    }
  throw std::invalid_argument(core::cat("--bound ", name,
                                        ": unknown name (use <region>.median|p95|max, horizon_jump, "
                                        "gpu_row_jump, gpu_cpu_difference; regions: space, night, twilight, "
                                        "horizon, ground, sky)"));
}

/// Messages for every --bound exceeded (empty: all held).
std::vector<std::string> check_bounds(const std::vector<std::string>& bounds, const RegionTable& all,
                                      const std::vector<GpuFrameResult>& frames) {
  std::vector<std::string> failed;
  for (const std::string& b : bounds) {
    const std::size_t eq = b.find('=');
    if (eq == std::string::npos) throw std::invalid_argument(core::cat("--bound ", b, ": expected NAME=VALUE"));
    const std::string name = b.substr(0, eq);
    const double limit = std::stod(b.substr(eq + 1));
    const double value = bounded_value(name, all, frames);
    if (!(value <= limit)) failed.push_back(core::cat(name, " = ", value, " exceeds its bound ", limit));
  }
  return failed;
}

}  // namespace

void validate_stress(const StressOptions& a, const TablesFor& tables_for) {
  for (const std::string& b : a.bounds) (void)bounded_value(b.substr(0, b.find('=')), {}, {});  // fail early on typos

  const auto start = std::chrono::steady_clock::now();
  std::vector<StressModel> models;
  for (const std::string& p : a.presets.empty() ? atmosphere::preset_names() : a.presets)
    models.push_back({p, atmosphere::load_preset(p), {}});
  for (std::size_t i = 0; i < a.random_models; ++i) {
    const auto params = random_atmosphere_parameters(a.seed, i);
    models.push_back({params["name"].get<std::string>(), atmosphere::resolve_atmosphere(params, "random"), {}});
    spdlog::info("{}: {}", models.back().label, params.dump());
  }

  for (StressModel& m : models) m.tables = tables_for(m.loaded.model).tables;
  const double tables_seconds = seconds_since(start);

  // CPU path: the sweep and an equal share of the random samples per model.
  std::vector<ModelResult> results;
  const std::size_t per_model = a.samples / models.size();
  {
    core::ProgressBar bar("stress (CPU)");
    std::size_t finished = 0;
    const std::size_t total = per_model * models.size();
    for (std::size_t k = 0; k < models.size(); ++k) {
      const atmosphere::lut::TableQueries q(models[k].loaded.model, models[k].tables);
      CpuStressOptions o;
      o.random_samples = per_model;
      o.seed = a.seed;
      o.stream = k;
      o.floor_sr = a.floor_sr;
      o.threads = a.threads;
      o.progress = [&](std::size_t done) {
        bar.update(models[k].label,
                   double(finished + std::min(done, per_model)) / double(std::max<std::size_t>(total, 1)));
      };
      const auto t0 = std::chrono::steady_clock::now();
      CpuStressResult r = run_cpu_stress(q, models[k].label, o);
      finished += per_model;
      results.push_back({models[k].label, r.regions, seconds_since(t0), 0.0});
    }
  }
  double cpu_seconds = 0.0;
  std::size_t cpu_samples = 0;
  for (const auto& r : results) cpu_seconds += r.cpu_seconds;
  for (const auto& r : results) cpu_samples += total(r.regions).samples;

  if (a.reference_samples > 0) {
    core::ProgressBar bar("stress (reference)");
    for (std::size_t k = 0; k < models.size(); ++k) {
      const atmosphere::lut::TableQueries q(models[k].loaded.model, models[k].tables);
      ReferenceComparisonOptions o;
      o.samples_per_region = a.reference_samples;
      o.seed = a.seed;
      o.stream = k;
      o.floor_sr = a.floor_sr;
      o.threads = a.threads;
      o.progress = [&](std::size_t done, std::size_t total) {
        bar.update(models[k].label, (double(k) + double(done) / double(total)) / double(models.size()));
      };
      const auto t0 = std::chrono::steady_clock::now();
      compare_with_reference(models[k].loaded.model, q, models[k].label, o, results[k].regions);
      results[k].reference_seconds = seconds_since(t0);
    }
  }

  // GPU path: one renderer, the tables handed over by model hash.
  std::vector<GpuFrameResult> frames;
  if (a.gpu) {
    std::optional<render::gl::HeadlessContext> context;
    try {
      context.emplace();
    } catch (const std::exception& e) {
      spdlog::warn("no GL context: the GPU path is skipped ({})", e.what());
    }
    if (context) {
      spdlog::info("GPU path on {}", context->renderer());
      std::map<std::string, const atmosphere::lut::LookupTables*> by_hash;
      for (const StressModel& m : models) by_hash[atmosphere::lookup_table_hash(m.loaded.model)] = &m.tables;
      render::RenderOptions options;
      options.colour = image::ColourMapping::direct;
      render::Renderer renderer(options, [&](const atmosphere::AtmosphereModel& model) {
        const auto it = by_hash.find(atmosphere::lookup_table_hash(model));
        if (it == by_hash.end()) throw std::runtime_error(core::cat("no tables for ", model.name));
        return *it->second;
      });
      core::ProgressBar bar("stress (GPU)");
      for (std::size_t k = 0; k < models.size(); ++k) {
        bar.update(models[k].label, double(k) / double(models.size()));
        const atmosphere::lut::TableQueries q(models[k].loaded.model, models[k].tables);
        auto f = run_gpu_stress(renderer, models[k].label, models[k].loaded, q, {a.floor_sr, 64});
        frames.insert(frames.end(), f.begin(), f.end());
      }
    }
  }

  fmt::print("{}", summary_table(results, frames));
  fmt::print("CPU: {} configurations in {:.1f} s ({:.2f} us each, {} threads); tables {:.1f} s; total {:.1f} s\n",
             cpu_samples, cpu_seconds, 1e6 * cpu_seconds / double(std::max<std::size_t>(cpu_samples, 1)),
             core::resolve_thread_count(a.threads), tables_seconds, seconds_since(start));
  if (!a.out.empty()) {
    std::filesystem::create_directories(a.out);
    write_file(std::filesystem::path(a.out) / "stress_regions.csv", regions_csv(results));
    write_file(std::filesystem::path(a.out) / "stress_gpu.csv", gpu_csv(frames));
    spdlog::info("wrote {}/stress_regions.csv and stress_gpu.csv", a.out);
  }

  const RegionStatistics t = total(all_models(results));
  std::size_t gpu_bad = 0;
  for (const auto& f : frames) gpu_bad += f.bad();
  const std::vector<std::string> failed = check_bounds(a.bounds, all_models(results), frames);
  for (const std::string& f : failed) fmt::print("BOUND EXCEEDED: {}\n", f);
  if (!failed.empty()) throw std::runtime_error(core::cat(failed.size(), " bound(s) exceeded: ", failed.front()));
  if (t.health.bad() > 0 || gpu_bad > 0)
    throw std::runtime_error(core::cat("numerical stability: ", t.health.bad(), " bad CPU values (NaN ", t.health.nan,
                                       ", Inf ", t.health.inf, ", negative ", t.health.negative, ", transmittance > 1 ",
                                       t.health.above_one, "), ", gpu_bad, " bad GPU pixel values"));
}

}  // namespace zenith::validate
