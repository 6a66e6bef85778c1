#pragma once
// The comma-separated tables of the validation's measured data: lines that
// start with '#' are comments (the source, the units), the first other line
// is the header, and every row has one cell per header name. Errors name the
// file, the line and the column, so a hand-edited or truncated file says
// where it went wrong.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace zenith::validate {

class CsvTable {
 public:
  struct Row {
    int line = 0;  ///< 1-based line in the file
    std::vector<std::string> cells;
  };

  /// Parses `text`; `source` names it in errors. Throws std::invalid_argument
  /// for a table without a header or rows, and for a row whose cell count
  /// differs from the header's.
  CsvTable(std::string_view text, std::string source);

  const std::string& source() const { return source_; }
  const std::vector<std::string>& header() const { return header_; }
  const std::vector<Row>& rows() const { return rows_; }

  /// The index of the column `name`; throws naming the file and its header.
  std::size_t column(std::string_view name) const;
  /// The cell of `row` in `column` as a finite number in [min, max]; throws
  /// naming the file, the line, the column and the allowed range.
  double number(const Row& row, std::size_t column, double min, double max) const;
  /// "FILE, line N, column NAME: what", for the errors of the table's readers.
  std::string where(const Row& row, std::size_t column) const;

 private:
  std::string source_;
  std::vector<std::string> header_;
  std::vector<Row> rows_;
};

}  // namespace zenith::validate
