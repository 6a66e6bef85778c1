// `zenith colour`: the colour of spectra read from a CSV — a measured sky, or
// one a study composed (a measured day sky times the model's eclipse ratio,
// scripts/eclipse-colour) — in the terms `zenith sample --colour` gives the
// model's sky: CIE 1931 x, y, the correlated colour temperature and Duv, and
// the effective blackbody temperature over a band (image/colour.h), so that a
// measurement and the model are read by the same code.
#include <fmt/format.h>
#include <fmt/os.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli_options.h"
#include "apps/commands.h"
#include "core/files.h"
#include "core/json_reader.h"
#include "image/colour.h"
#include "validate/csv_table.h"

namespace zenith::app {
namespace {

struct ColourArgs {
  std::string spectrum, out = "-";
  std::vector<double> band_nm = {410.0, 800.0};
};

/// A temperature for the CSV: +∞ (bluer than any Planck curve) as "inf".
std::string kelvin_cell(double kelvin) { return std::isinf(kelvin) ? "inf" : fmt::format("{:.0f}", kelvin); }

void run_colour(const ColourArgs& a) {
  const double from_nm = a.band_nm[0], to_nm = a.band_nm[1];
  check_wavelength_band("--band-nm", a.band_nm);
  // CsvTable's errors name the file, the line and the column.
  const validate::CsvTable table(core::file_bytes(a.spectrum), a.spectrum);
  if (table.header().size() < 2 || table.header().front() != "wavelength_nm")
    throw ConfigError(a.spectrum, "header",
                      "expected 'wavelength_nm' and at least one column of spectral values, got '" +
                          fmt::format("{}", fmt::join(table.header(), ",")) + "'");
  std::vector<double> wavelengths_nm;
  std::vector<std::vector<double>> columns(table.header().size() - 1);
  for (const validate::CsvTable::Row& row : table.rows()) {
    const double nm = table.number(row, 0, 100.0, 100000.0);
    if (!wavelengths_nm.empty() && nm <= wavelengths_nm.back())
      throw std::invalid_argument(table.where(row, 0) + ": the wavelengths must increase from row to row");
    wavelengths_nm.push_back(nm);
    for (std::size_t c = 1; c < table.header().size(); ++c)
      columns[c - 1].push_back(table.number(row, c, 0.0, HUGE_VAL));
  }

  // The chromaticity needs the visible spanned; a narrower spectrum still has
  // an effective temperature over its band.
  const bool chromaticity = image::colour_spectrum_problem(wavelengths_nm).empty();
  std::string csv = "column,x,y,CCT_K,Duv,T_eff_K\n";
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const std::string& name = table.header()[c + 1];
    std::string cells = ",,,";
    double effective = 0.0;
    try {
      if (chromaticity) {
        const image::Chromaticity xy = image::spectrum_chromaticity(wavelengths_nm, columns[c]);
        const image::ColourTemperature t = image::correlated_colour_temperature(xy);
        cells = fmt::format("{:.5f},{:.5f},{},{:.5f}", xy.x, xy.y, kelvin_cell(t.kelvin), t.duv);
      }
      effective = image::effective_blackbody_temperature_K(wavelengths_nm, columns[c], from_nm, to_nm);
    } catch (const std::invalid_argument& e) {
      throw ConfigError(a.spectrum, "column " + name, e.what());
    }
    csv += fmt::format("{},{},{}\n", name, cells, kelvin_cell(effective));
  }
  if (a.out == "-") {
    fmt::print("{}", csv);
  } else {
    fmt::output_file(a.out).print("{}", csv);
  }
}

}  // namespace

void register_colour_command(CLI::App& app) {
  auto args = std::make_shared<ColourArgs>();
  CLI::App* cmd = app.add_subcommand(
      "colour",
      "The colour of spectra from a CSV (a measured sky, or one composed from zenith's output): CIE 1931 x, y, "
      "correlated colour temperature and Duv, effective blackbody temperature over a band");
  cmd->add_option("--spectrum", args->spectrum,
                  "CSV: a header 'wavelength_nm,NAME[,NAME...]', then one row per wavelength (increasing) with "
                  "each column's spectral radiance in any one unit; lines starting with '#' are comments")
      ->required();
  add_wavelength_band_option(cmd, "--band-nm", args->band_nm,
                             "The effective temperature's band: first,last wavelength [nm] (default 410,800, as "
                             "Dandekar & Turtle 1971; at least 3 of the spectrum's wavelengths inside)");
  cmd->add_option("--out", args->out, "Output CSV file ('-' for standard output)");
  cmd->callback([args] { run_colour(*args); });
}

}  // namespace zenith::app
