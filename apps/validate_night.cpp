// `zenith validate night` (docs/night-sky.md): the command line of the night
// sky's checks against published figures (validate/night_validation.h).
#include <memory>
#include <string>

#include "apps/commands.h"
#include "apps/validation_tables.h"
#include "validate/night_validation.h"

namespace zenith::app {
namespace {

struct ValidateNightArgs {
  validate::NightValidationOptions validation;
  ValidationTableArgs tables;
};

void run_validate_night(const ValidateNightArgs& a) {
  validate::validate_night(a.validation, validation_tables(a.tables.request(a.validation.tables)));
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
  add_validation_table_options(cmd, args->validation.tables, args->tables);
  cmd->add_flag("--no-plots", args->validation.no_plots, "Write the data but no gnuplot scripts or PNG");
  cmd->callback([args] { run_validate_night(*args); });
}

}  // namespace zenith::app
