#include "validate/csv_table.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/strings.h"

namespace zenith::validate {
namespace {

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(trimmed(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) return cells;
    start = comma + 1;
  }
}

}  // namespace

CsvTable::CsvTable(std::string_view text, std::string source) : source_(std::move(source)) {
  std::istringstream in{std::string(text)};
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (trimmed(line).empty() || line[0] == '#') continue;
    std::vector<std::string> cells = cells_of(line);
    if (header_.empty()) {
      header_ = std::move(cells);
      continue;
    }
    if (cells.size() != header_.size())
      throw std::invalid_argument(
          core::cat(source_, ", line ", line_no, ": ", cells.size(), " cells where the header has ", header_.size()));
    rows_.push_back({line_no, std::move(cells)});
  }
  if (header_.empty() || rows_.empty()) throw std::invalid_argument(core::cat(source_, ": no header or no rows"));
}

std::size_t CsvTable::column(std::string_view name) const {
  for (std::size_t c = 0; c < header_.size(); ++c)
    if (header_[c] == name) return c;
  std::string names;
  for (const std::string& h : header_) names += (names.empty() ? "" : ",") + h;
  if (names.size() > 120) names = names.substr(0, 117) + "...";
  throw std::invalid_argument(core::cat(source_, ": no column '", name, "' in the header (", names, ")"));
}

std::string CsvTable::where(const Row& row, std::size_t column) const {
  return core::cat(source_, ", line ", row.line, ", column ", header_.at(column));
}

double CsvTable::number(const Row& row, std::size_t column, double min, double max) const {
  const std::string& cell = row.cells.at(column);
  std::size_t used = 0;
  double v = std::nan("");
  try {
    v = std::stod(cell, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != cell.size() || !std::isfinite(v))
    throw std::invalid_argument(core::cat(where(row, column), ": '", cell, "' is not a number"));
  if (v < min || v > max)
    throw std::invalid_argument(core::cat(where(row, column), ": ", cell, " is outside [", min, ", ", max, "]"));
  return v;
}

}  // namespace zenith::validate
