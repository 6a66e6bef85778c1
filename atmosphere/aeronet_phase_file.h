#pragma once
// AERONET's export of the aerosol phase functions it retrieves from
// almucantar scans of the sky (".pfn", Version 2 inversion products, "Phase
// Functions - Total Mode"): three header lines (the date, the site with its
// coordinates and PIs; the level; the product), a line of column names, then
// one line per retrieval — Date(dd-mm-yyyy), Time(hh:mm:ss), Julian_Day, then
// P at each angle and wavelength in columns named "<angle>[<wavelength>nm]"
// (angles 0–180°, AERONET's scale: ½ ∫ P sin θ dθ = 1), then the retrieval's
// diagnostics (sky_error, tau440(measured), ...), read here only as text.
//
// The reader takes the file as AERONET writes it and refuses anything else
// with the file, the line and the column: a retrieval with a missing value
// (AERONET writes -999 or N/A), a wavelength whose angles differ from the
// others', a line with fewer fields than the header.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "atmosphere/tabulated_phase.h"

namespace zenith::atmosphere {

struct AeronetPhaseFunctions {
  std::string site;                ///< the first line's Locations=
  std::string level;               ///< the second line ("Level 1.5 Almucantar Retrievals, Version 2")
  std::vector<double> angles_deg;  ///< the scattering angles, the same at every wavelength
  std::vector<double> wavelengths_nm;
  struct Retrieval {
    std::string date, time;                   ///< as written (dd:mm:yyyy, hh:mm:ss UTC)
    std::vector<std::vector<double>> values;  ///< [wavelength][angle], AERONET's scale
    /// The other columns after Julian_Day, by name, as written (e.g.
    /// "tau440(measured)", "alpha440-870", "sky_error").
    std::map<std::string, std::string> diagnostics;
  };
  std::vector<Retrieval> retrievals;  ///< at least one

  /// The mean of the retrievals at each wavelength: TabulatedPhase's columns.
  std::vector<TabulatedPhase::Column> mean_columns() const;
};

/// Reads an AERONET phase-function file. Throws zenith::ConfigError naming the
/// file, the line and the column on anything it cannot read.
AeronetPhaseFunctions read_aeronet_phase_functions(const std::filesystem::path& path);

}  // namespace zenith::atmosphere
