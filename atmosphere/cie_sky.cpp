#include "atmosphere/cie_sky.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "atmosphere/constants.h"
#include "atmosphere/reference_data.h"
#include "core/strings.h"

namespace zenith::atmosphere {
namespace {

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  for (std::string& c : cells) {
    const auto first = c.find_first_not_of(" \t\r");
    const auto last = c.find_last_not_of(" \t\r");
    c = first == std::string::npos ? std::string() : c.substr(first, last - first + 1);
  }
  return cells;
}

double parse_number(const std::string& cell, int line_no) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(cell, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != cell.size() || !std::isfinite(v))
    throw std::invalid_argument(core::cat("CIE sky types, line ", line_no, ": '", cell, "' is not a number"));
  return v;
}

}  // namespace

std::vector<CieSkyType> parse_cie_sky_types(std::string_view csv_text) {
  const std::vector<std::string> expected = {"type", "a", "b", "c", "d", "e", "description"};
  std::istringstream in{std::string(csv_text)};
  std::string line;
  std::vector<CieSkyType> types;
  bool header_seen = false;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> cells = split_csv_line(line);
    if (!header_seen) {
      if (cells != expected)
        throw std::invalid_argument(
            core::cat("CIE sky types, line ", line_no, ": expected the header 'type,a,b,c,d,e,description'"));
      header_seen = true;
      continue;
    }
    if (cells.size() < 6)
      throw std::invalid_argument(core::cat("CIE sky types, line ", line_no, ": expected 7 columns"));
    CieSkyType t;
    const double number = parse_number(cells[0], line_no);
    if (number != std::floor(number) || number < 1.0 || number > 99.0)
      throw std::invalid_argument(core::cat("CIE sky types, line ", line_no, ": bad type number '", cells[0], "'"));
    t.number = static_cast<int>(number);
    t.a = parse_number(cells[1], line_no);
    t.b = parse_number(cells[2], line_no);
    t.c = parse_number(cells[3], line_no);
    t.d = parse_number(cells[4], line_no);
    t.e = parse_number(cells[5], line_no);
    for (std::size_t i = 6; i < cells.size(); ++i) t.description += (i > 6 ? "," : "") + cells[i];
    types.push_back(std::move(t));
  }
  if (!header_seen || types.empty()) throw std::invalid_argument("CIE sky types: no header or no rows");
  std::sort(types.begin(), types.end(), [](const CieSkyType& x, const CieSkyType& y) { return x.number < y.number; });
  return types;
}

std::vector<CieSkyType> cie_general_sky_types() {
  return parse_cie_sky_types(embedded_file("data/cie_general_sky_types.csv"));
}

CieSkyType cie_general_sky_type(int number) {
  for (CieSkyType& t : cie_general_sky_types())
    if (t.number == number) return t;
  throw std::out_of_range(core::cat("no CIE standard general sky type ", number, " (the standard defines 1..15)"));
}

// (V2) φ(Z) = 1 + a·exp(b / cos Z); at the horizon b / cos Z → −∞ (b < 0), so φ → 1.
double cie_gradation(const CieSkyType& type, double zenith_rad) {
  const double cos_z = std::cos(zenith_rad);
  if (cos_z <= 0.0) return 1.0;
  return 1.0 + type.a * std::exp(type.b / cos_z);
}

// (V3) f(χ) = 1 + c·(exp(d·χ) − exp(d·π/2)) + e·cos²χ.
double cie_indicatrix(const CieSkyType& type, double sun_distance_rad) {
  const double cos_chi = std::cos(sun_distance_rad);
  return 1.0 + type.c * (std::exp(type.d * sun_distance_rad) - std::exp(type.d * kPi / 2.0)) +
         type.e * cos_chi * cos_chi;
}

// (V4) cos χ = cos Z cos Z_s + sin Z sin Z_s cos α, clamped against rounding.
double cie_sun_distance_rad(double view_zenith_rad, double azimuth_from_sun_rad, double sun_zenith_rad) {
  const double cos_chi = std::cos(view_zenith_rad) * std::cos(sun_zenith_rad) +
                         std::sin(view_zenith_rad) * std::sin(sun_zenith_rad) * std::cos(azimuth_from_sun_rad);
  return std::acos(std::clamp(cos_chi, -1.0, 1.0));
}

// (V1) L/L_z = f(χ)·φ(Z) / (f(Z_s)·φ(0)): the zenith is at distance Z_s from the sun.
double cie_relative_luminance(const CieSkyType& type, double view_zenith_rad, double azimuth_from_sun_rad,
                              double sun_zenith_rad) {
  const double chi = cie_sun_distance_rad(view_zenith_rad, azimuth_from_sun_rad, sun_zenith_rad);
  return cie_indicatrix(type, chi) * cie_gradation(type, view_zenith_rad) /
         (cie_indicatrix(type, sun_zenith_rad) * cie_gradation(type, 0.0));
}

}  // namespace zenith::atmosphere
