// `zenith validate` (docs/RESULTS.md): measured evidence that the physics is
// right — `validate measured` compares the sky with measured skies
// (validate/measured_sky_validation.h, docs/validation.md), `validate cie`
// compares the Earth presets with the CIE standard general sky
// (validate/cie_validation.h), `validate night` checks the night sky against
// published figures (validate/night_validation.h, docs/night-sky.md),
// `validate eclipse` holds the sky of a total eclipse to measured totality
// skies (validate/eclipse_validation.h), `validate stress`
// (apps/validate_stress.cpp) sweeps the numerically hard corners on the CPU
// and GPU paths.
#include "apps/commands.h"
#include "apps/validation_tables.h"
#include "validate/cie_validation.h"
#include "validate/eclipse_validation.h"
#include "validate/measured_sky_validation.h"
#include "validate/night_validation.h"

namespace zenith::app {
namespace {

void register_validate_cie(CLI::App& validate) {
  const auto [cmd, args] = add_validation_check<validate::CieValidationOptions>(
      validate, "cie",
      "Relative sky luminance L/Lz of the Earth presets against the CIE standard general sky (type 12)",
      validate::validate_cie);
  cmd->add_option("--preset", args->validation.presets,
                  "Preset name or atmosphere JSON file (repeatable; default earth-advanced and earth-standard)")
      ->delimiter(',');
  cmd->add_option("--sun-zenith", args->validation.sun_zeniths_deg,
                  "Sun zenith angles [deg], comma-separated (default "
                  "20,30,45,60,70,80)")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 89.0));
  cmd->add_flag("--csv", args->validation.csv_stdout,
                "Print the per-case table as CSV on stdout instead of the text summary");
  cmd->add_flag("--no-variants", args->validation.no_variants,
                "Only the presets as given (no classic-Rayleigh and geometric-air-mass variants)");
  cmd->add_option("--zenith-step", args->validation.zenith_step_deg, "Step of the view zenith angle [deg]")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 45.0));
  cmd->add_option("--exclude-sun-deg", args->validation.exclude_sun_deg,
                  "Leave out directions closer than this to the sun [deg]")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 30.0));
}

void register_validate_night(CLI::App& validate) {
  const auto [cmd, args] = add_validation_check<validate::NightValidationOptions>(
      validate, "night",
      "Positions, refraction, extinction, twilight brightness and star visibility against published figures",
      validate::validate_night);
  cmd->add_option("--preset", args->validation.preset, "The Earth atmosphere for twilight and stars")
      ->capture_default_str();
}

void register_validate_measured(CLI::App& validate) {
  const auto [cmd, args] = add_validation_check<validate::MeasuredSkyOptions>(
      validate, "measured",
      "Spectral sky radiance against Kider et al. 2014's measured skies (Cornell, 2013-05-27), with Bruneton "
      "2017's metric and the published models' scores",
      validate::validate_measured);
  cmd->add_option("--atmosphere", args->validation.atmosphere,
                  "Preset or atmosphere file whose wavelengths_nm hold the measured wavelengths (default: the day's "
                  "atmosphere, validate/data/cornell_2013-05-27.json)");
  cmd->add_option("--measurements", args->validation.measurements,
                  "Measured radiance CSV (default: Kider 2014, compiled in; with --suns)");
  cmd->add_option("--suns", args->validation.suns, "The captures' sun CSV (with --measurements)");
  cmd->add_option("--sun-spectrum", args->validation.sun_spectrum,
                  "Extraterrestrial sun CSV (lambda_nm, irradiance_W_m2_nm at every measured wavelength; default: "
                  "ASTM G173 in the evaluation's 11.75 nm bins)");
  cmd->add_option("--sun-distance-au", args->validation.sun_distance_au,
                  "The Sun's distance at the captures for the day's sun [au, 0.983..1.017] (default: from the "
                  "ephemeris for the compiled-in captures, 1 for --measurements)");
  cmd->add_option("--reference-samples", args->validation.reference_samples,
                  "Also check the tables against the reference solver with this many paths per wavelength (0: no)")
      ->check(CLI::Range(std::size_t{0}, std::size_t{1} << 24));
  cmd->add_option("--reference-directions", args->validation.reference_directions,
                  "Directions of the reference check, spread over the capture's rings")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1}, std::size_t{81}));
  cmd->add_option("--reference-capture", args->validation.reference_capture,
                  "The capture of the reference check and of the rings plot")
      ->capture_default_str();
}

void register_validate_eclipse(CLI::App& validate) {
  auto [cmd, args] = add_validation_check<validate::EclipseValidationOptions>(
      validate, "eclipse",
      "The sky of the total eclipse of 2017-08-21, the reference solver's and the tables', against measured totality "
      "skies",
      validate::validate_eclipse);
  cmd->add_option("--samples", args->validation.samples, "Paths per wavelength in totality (a tenth outside it)")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1000}, std::size_t{1} << 30));
}

}  // namespace

void register_validate_command(CLI::App& app) {
  CLI::App* validate = app.add_subcommand("validate", "Accuracy and numerical-stability validation (docs/RESULTS.md)");
  validate->require_subcommand(1);
  register_validate_cie(*validate);
  register_validate_stress(*validate);
  register_validate_night(*validate);
  register_validate_measured(*validate);
  register_validate_eclipse(*validate);
}

}  // namespace zenith::app
