// `zenith validate stress` (docs/validation.md "Numerical stability"): the
// command line of the stress test (validate/stress_run.h).
#include <memory>
#include <string>

#include "apps/cli_options.h"
#include "apps/commands.h"
#include "apps/validation_tables.h"
#include "atmosphere/named_inputs.h"
#include "validate/stress_run.h"

namespace zenith::app {
namespace {

struct StressArgs {
  validate::StressOptions stress;
  std::string tables = "paper", cache_dir;
  bool cpu_precompute = false;
};

void run_stress(const StressArgs& a) {
  render::TableRequest request;
  atmosphere::apply_table_set(a.tables, request.options);
  request.backend = a.cpu_precompute ? render::PrecomputeBackend::Cpu : render::PrecomputeBackend::Gpu;
  if (!a.cache_dir.empty()) request.cache_directory = a.cache_dir;
  validate::validate_stress(a.stress, validation_tables(std::move(request)));
}

}  // namespace

void register_validate_stress(CLI::App& validate) {
  auto args = std::make_shared<StressArgs>();
  CLI::App* cmd = validate.add_subcommand(
      "stress", "Numerical stability: NaN/Inf/negative counts, horizon jumps and errors per region, CPU and GPU paths");
  cmd->add_option("--samples", args->stress.samples,
                  "CPU configurations in all (split over the models), after the sweep")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 36));
  cmd->add_option("--seed", args->stress.seed, "Random seed (samples and random parameter sets)");
  cmd->add_option("--tables", args->tables,
                  "Table sizes: paper (default), twilight (128 mu_s texels and 200 ray samples, for dusk and night), "
                  "small, large")
      ->check(CLI::IsMember(atmosphere::table_size_names()));
  cmd->add_option("--presets", args->stress.presets, "Presets to stress (default: all)")->delimiter(',');
  cmd->add_option("--random-models", args->stress.random_models, "Random parameter sets besides the presets")
      ->check(CLI::Range(0, 100));
  cmd->add_option("--reference-samples", args->stress.reference_samples,
                  "Single-scattering comparisons with the exact quadrature per region and model")
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--floor", args->stress.floor_sr,
                  "Absolute floor of relative errors [sr^-1 per unit solar irradiance]")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--gpu,!--no-gpu", args->stress.gpu, "Also render frames on the GPU path (default on)");
  add_cpu_precompute_flag(cmd, args->cpu_precompute);
  cmd->add_option("--cache", args->cache_dir, "Table cache directory (default $XDG_CACHE_HOME/zenith)");
  cmd->add_option("--threads", args->stress.threads, "CPU threads (default: all)");
  cmd->add_option("--out", args->stress.out, "Write stress_regions.csv and stress_gpu.csv into this directory");
  cmd->add_option("--bound", args->stress.bounds,
                  "Fail when a measured figure exceeds VALUE: NAME=VALUE with NAME <region>.median|p95|max, "
                  "horizon_jump, gpu_row_jump or gpu_cpu_difference (repeatable)");
  cmd->callback([args] { run_stress(*args); });
}

}  // namespace zenith::app
