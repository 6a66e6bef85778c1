// `zenith validate` (docs/RESULTS.md): measured evidence that the physics is
// right — `validate cie` (apps/validate_cie.cpp) compares the Earth presets
// with the CIE standard general sky, `validate stress` (apps/validate_stress.cpp)
// sweeps the numerically hard corners on the CPU and GPU paths, `validate night`
// (apps/validate_night.cpp) checks the night sky against published figures.
#include "apps/commands.h"

namespace zenith::app {

void register_validate_command(CLI::App& app) {
  CLI::App* validate = app.add_subcommand("validate", "Accuracy and numerical-stability validation (docs/RESULTS.md)");
  validate->require_subcommand(1);
  register_validate_cie(*validate);
  register_validate_stress(*validate);
  register_validate_night(*validate);
}

}  // namespace zenith::app
