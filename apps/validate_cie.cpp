// `zenith validate cie` (docs/validation.md): the command line of the
// comparison with the CIE standard general sky (validate/cie_validation.h).
#include <memory>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "apps/validation_tables.h"
#include "validate/cie_validation.h"

namespace zenith::app {
namespace {

struct ValidateCieArgs {
  validate::CieValidationOptions validation;
  ValidationTableArgs tables;
};

void run_validate_cie(const ValidateCieArgs& a) {
  validate::validate_cie(a.validation, validation_tables(a.tables.request(a.validation.tables)));
}

}  // namespace

void register_validate_cie(CLI::App& validate) {
  auto args = std::make_shared<ValidateCieArgs>();
  CLI::App* cmd = validate.add_subcommand(
      "cie", "Relative sky luminance L/Lz of the Earth presets against the CIE standard general sky (type 12)");
  cmd->add_option("--preset", args->validation.presets,
                  "Preset name or atmosphere JSON file (repeatable; default earth-advanced and earth-standard)")
      ->delimiter(',');
  cmd->add_option("--sun-zenith", args->validation.sun_zeniths_deg,
                  "Sun zenith angles [deg], comma-separated (default "
                  "20,30,45,60,70,80)")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 89.0));
  cmd->add_option("--out", args->validation.out_dir, "Output directory (CSV, gnuplot scripts, PNG)")
      ->capture_default_str();
  cmd->add_flag("--csv", args->validation.csv_stdout,
                "Print the per-case table as CSV on stdout instead of the text summary");
  add_validation_table_options(cmd, args->validation.tables, args->tables);
  cmd->add_flag("--no-variants", args->validation.no_variants,
                "Only the presets as given (no classic-Rayleigh and geometric-air-mass variants)");
  cmd->add_flag("--no-plots", args->validation.no_plots, "Write the data but no gnuplot scripts or PNG");
  cmd->add_option("--zenith-step", args->validation.zenith_step_deg, "Step of the view zenith angle [deg]")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 45.0));
  cmd->add_option("--exclude-sun-deg", args->validation.exclude_sun_deg,
                  "Leave out directions closer than this to the sun [deg]")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 30.0));
  cmd->callback([args] { run_validate_cie(*args); });
}

}  // namespace zenith::app
