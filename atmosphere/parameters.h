#pragma once
// Atmosphere parameter sets (JSON) and their resolution into an AtmosphereModel.
//
// Two modes, as in the paper (section 6.1):
//  * standard — coefficients given directly: β_R^scat(λ), β_M^scat(λ), β_M^ext(λ),
//    scale heights, Mie phase constants, radii, ground albedo, optional absorbers.
//  * advanced — physical quantities from which the coefficients are derived:
//    refractive index, number density (or pressure and temperature, or mass
//    density and molar mass), depolarization, molecular absorption (eq. 12),
//    O2 (eq. 13–14) and ozone (eq. 15) absorption, turbidity-driven Mie
//    scattering (eq. 17), anomalous-diffraction Mie extinction (eq. 18–20),
//    wavelength-dependent double Henyey–Greenstein phase (eq. 16).
// The schema is documented in docs/atmosphere-config.md.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "atmosphere/atmosphere_model.h"

namespace zenith::atmosphere {

/// The paper's working wavelengths: red, green, blue.
inline const std::vector<double> kDefaultWavelengths_nm = {680.0, 550.0, 440.0};

struct LoadOptions {
  /// Overrides the file's `wavelengths_nm` (e.g. for spectral rendering).
  std::optional<std::vector<double>> wavelengths_nm;
};

struct LoadedAtmosphere {
  AtmosphereModel model;
  std::string mode;                     ///< "standard" or "advanced"
  nlohmann::json parameters;            ///< the parameters as given (for reports and shows)
  std::vector<std::string> warnings;    ///< e.g. a spectral table extrapolated beyond its samples
  std::vector<std::string> derivation;  ///< human-readable notes on derived quantities (advanced mode)
};

/// Resolves a parameter set. `source` names it in error messages (a file path
/// or "preset:NAME"). Throws zenith::ConfigError on any invalid input.
LoadedAtmosphere resolve_atmosphere(const nlohmann::json& parameters, const std::string& source,
                                    const LoadOptions& options = {});

/// Reads and resolves a JSON file.
LoadedAtmosphere load_atmosphere_file(const std::string& path, const LoadOptions& options = {});

/// Names of the built-in presets (configs/atmospheres/*.json, compiled in).
std::vector<std::string> preset_names();
/// The JSON of a built-in preset; throws ConfigError listing the presets if unknown.
nlohmann::json preset_parameters(const std::string& name);
LoadedAtmosphere load_preset(const std::string& name, const LoadOptions& options = {});

}  // namespace zenith::atmosphere
