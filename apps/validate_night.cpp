// `zenith validate night` (docs/night-sky.md): the command line of the night
// sky's checks against published figures (validate/night_validation.h).
#include <memory>
#include <string>

#include "apps/cli_options.h"
#include "apps/commands.h"
#include "apps/validation_tables.h"
#include "offline/output_rendering.h"
#include "validate/night_validation.h"

namespace zenith::app {
namespace {

struct ValidateNightArgs {
  validate::NightValidationOptions validation;
  std::string cache_dir;
  int orders = atmosphere::lut::kDefaultScatteringOrders;
  bool cpu = false, no_cache = false;
  unsigned threads = 0;
};

void run_validate_night(const ValidateNightArgs& a) {
  render::TableRequest request = make_table_request(a.validation.tables, a.orders, a.cpu, !a.no_cache, a.cache_dir);
  request.options.threads = a.threads;
  validate::validate_night(a.validation, validation_tables(std::move(request)));
}

}  // namespace

void register_validate_night(CLI::App& validate) {
  auto args = std::make_shared<ValidateNightArgs>();
  CLI::App* cmd = validate.add_subcommand(
      "night", "Positions, refraction, extinction, twilight brightness and star visibility against published figures");
  cmd->add_option("--preset", args->validation.preset, "The Earth atmosphere for twilight and stars")
      ->capture_default_str();
  cmd->add_option("--out", args->validation.out_dir, "Output directory (CSV, gnuplot scripts, PNG)")
      ->capture_default_str();
  add_table_options(cmd, args->validation.tables, args->orders, args->cache_dir);
  cmd->add_flag("--cpu", args->cpu, "Precompute on the CPU instead of the GPU (when not cached)");
  cmd->add_flag("--no-cache", args->no_cache, "Neither read nor write the table cache");
  cmd->add_option("--threads", args->threads, "CPU threads (default: all)");
  cmd->add_flag("--no-plots", args->validation.no_plots, "Write the data but no gnuplot scripts or PNG");
  cmd->callback([args] { run_validate_night(*args); });
}

}  // namespace zenith::app
