#include "atmosphere/aeronet_phase_file.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/json_reader.h"

namespace zenith::atmosphere {

namespace {

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) {
    if (!field.empty() && field.back() == '\r') field.pop_back();
    fields.push_back(field);
  }
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

/// The whole text as a number, or false.
bool parse_number(const std::string& text, double* value) {
  std::size_t used = 0;
  try {
    *value = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size() && std::isfinite(*value);
}

/// "<angle>[<wavelength>nm]" → angle and wavelength, or false.
bool parse_phase_column(const std::string& name, double* angle_deg, double* wavelength_nm) {
  const std::size_t open = name.find('[');
  if (open == std::string::npos || name.size() < open + 4 || name.compare(name.size() - 3, 3, "nm]") != 0) return false;
  return parse_number(name.substr(0, open), angle_deg) &&
         parse_number(name.substr(open + 1, name.size() - open - 4), wavelength_nm);
}

}  // namespace

std::vector<TabulatedPhase::Column> AeronetPhaseFunctions::mean_columns() const {
  std::vector<TabulatedPhase::Column> columns;
  for (std::size_t w = 0; w < wavelengths_nm.size(); ++w) {
    TabulatedPhase::Column c{wavelengths_nm[w], std::vector<double>(angles_deg.size(), 0.0)};
    for (const Retrieval& r : retrievals)
      for (std::size_t a = 0; a < angles_deg.size(); ++a) c.values[a] += r.values[w][a];
    for (double& v : c.values) v /= static_cast<double>(retrievals.size());
    columns.push_back(std::move(c));
  }
  return columns;
}

AeronetPhaseFunctions read_aeronet_phase_functions(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path);
  if (!in) throw ConfigError(file, "(file)", "cannot open file");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  auto fail = [&](std::size_t line, const std::string& column, const std::string& message) {
    throw ConfigError(file, "line " + std::to_string(line + 1) + (column.empty() ? "" : ", column " + column), message);
  };
  if (lines.size() < 5)
    fail(lines.size(), "",
         "an AERONET phase-function file has 3 header lines, the column names and "
         "at least one retrieval; this one has " +
             std::to_string(lines.size()) + " lines");

  AeronetPhaseFunctions out;
  for (const std::string& field : split_commas(lines[0]))
    if (field.rfind("Locations=", 0) == 0) out.site = field.substr(10);
  out.level = lines[1];

  // The column names: the phase columns, grouped by wavelength in file order.
  const std::vector<std::string> names = split_commas(lines[3]);
  if (names.size() < 4 || names[0].rfind("Date", 0) != 0 || names[1].rfind("Time", 0) != 0)
    fail(3, "", "the column names must start with Date(dd-mm-yyyy),Time(hh:mm:ss): is this an AERONET file?");
  std::map<double, std::vector<std::pair<double, std::size_t>>> by_wavelength;  // angle, column index
  std::vector<double> order;
  for (std::size_t c = 0; c < names.size(); ++c) {
    double angle = 0.0, wavelength = 0.0;
    if (!parse_phase_column(names[c], &angle, &wavelength)) continue;
    if (!(angle >= 0.0 && angle <= 180.0) || !(wavelength > 0.0))
      fail(3, "'" + names[c] + "'", "angle must be in [0, 180] deg and the wavelength > 0 nm");
    if (!by_wavelength.contains(wavelength)) order.push_back(wavelength);
    auto& columns = by_wavelength[wavelength];
    if (!columns.empty() && !(angle > columns.back().first))
      fail(3, "'" + names[c] + "'", "angles must increase within a wavelength");
    columns.emplace_back(angle, c);
  }
  if (order.empty()) fail(3, "", "no phase-function column (\"<angle>[<wavelength>nm]\")");
  for (const auto& [angle, c] : by_wavelength[order.front()]) out.angles_deg.push_back(angle);
  for (double wl : order) {
    const auto& columns = by_wavelength[wl];
    bool same = columns.size() == out.angles_deg.size();
    for (std::size_t a = 0; same && a < columns.size(); ++a) same = columns[a].first == out.angles_deg[a];
    if (!same)
      fail(3, "'" + names[columns.front().second] + "'",
           "the angles at " + std::to_string(wl) + " nm differ from those at " + std::to_string(order.front()) + " nm");
  }
  out.wavelengths_nm = order;

  for (std::size_t l = 4; l < lines.size(); ++l) {
    if (lines[l].find_first_not_of(" \t") == std::string::npos) continue;
    const std::vector<std::string> fields = split_commas(lines[l]);
    if (fields.size() < names.size())
      fail(l, "",
           "has " + std::to_string(fields.size()) + " fields where the column names give " +
               std::to_string(names.size()));
    AeronetPhaseFunctions::Retrieval r{fields[0], fields[1], {}, {}};
    for (std::size_t c = 3; c < names.size(); ++c) {
      double angle = 0.0, wavelength = 0.0;
      if (!parse_phase_column(names[c], &angle, &wavelength)) r.diagnostics[names[c]] = fields[c];
    }
    for (double wl : order) {
      std::vector<double> values;
      for (const auto& [angle, c] : by_wavelength[wl]) {
        double v = 0.0;
        if (!parse_number(fields[c], &v) || !(v > 0.0))
          fail(l, "'" + names[c] + "'",
               "'" + fields[c] +
                   "' is not a phase-function value (a number > 0; AERONET writes -999 or N/A where "
                   "it has none)");
        values.push_back(v);
      }
      r.values.push_back(std::move(values));
    }
    out.retrievals.push_back(std::move(r));
  }
  if (out.retrievals.empty()) fail(lines.size(), "", "no retrieval after the column names");
  return out;
}

}  // namespace zenith::atmosphere
