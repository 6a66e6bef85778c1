// `zenith validate` (docs/validation.md): measured evidence that the physics is
// right — `validate stress` (apps/validate_stress.cpp) sweeps the numerically
// hard corners on the CPU and GPU paths.
#include "apps/commands.h"

namespace zenith::app {

void register_validate_command(CLI::App& app) {
  CLI::App* validate = app.add_subcommand("validate", "Accuracy and numerical-stability validation (docs/RESULTS.md)");
  validate->require_subcommand(1);
  register_validate_stress(*validate);
}

}  // namespace zenith::app
