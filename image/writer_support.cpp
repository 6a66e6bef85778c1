#include "image/writer_support.h"

#include <set>
#include <stdexcept>
#include <system_error>

namespace zenith::image::detail {

std::filesystem::path partial_path_for(const std::filesystem::path& path) {
  std::filesystem::path partial = path;
  partial += ".partial";
  return partial;
}

std::string prefix(const std::filesystem::path& path) { return path.string() + ": "; }

void check_dimensions(const std::filesystem::path& path, int width, int height, long long max_side) {
  if (width < 1 || height < 1 || width > max_side || height > max_side)
    throw std::invalid_argument(prefix(path) + "image size " + std::to_string(width) + "x" + std::to_string(height) +
                                " px: each side must be in [1, " + std::to_string(max_side) + "]");
}

void check_unique_names(const std::filesystem::path& path, const ImageAttributes& attributes) {
  std::set<std::string> seen;
  for (const auto& [name, value] : attributes)
    if (!seen.insert(name).second)
      throw std::invalid_argument(prefix(path) + "attribute '" + name + "' is given twice");
}

void check_row_block(const std::filesystem::path& path, int width, int height, int rows_written, int row_count,
                     std::size_t value_count, bool open) {
  if (!open) throw std::logic_error(prefix(path) + "write_rows after finish() or after a failed write");
  if (row_count < 0) throw std::invalid_argument(prefix(path) + "negative row count " + std::to_string(row_count));
  if (row_count > height - rows_written)
    throw std::logic_error(prefix(path) + "rows " + std::to_string(rows_written) + ".." +
                           std::to_string(rows_written + row_count - 1) + " written to a " + std::to_string(height) +
                           "-row image");
  const std::size_t expected = std::size_t(width) * std::size_t(row_count) * 3;
  if (value_count != expected)
    throw std::invalid_argument(prefix(path) + std::to_string(row_count) + " rows of " + std::to_string(width) +
                                " RGB pixels need " + std::to_string(expected) + " floats, got " +
                                std::to_string(value_count));
}

void check_complete(const std::filesystem::path& path, int height, int rows_written, bool open) {
  if (!open) throw std::logic_error(prefix(path) + "finish() after finish() or after a failed write");
  if (rows_written != height)
    throw std::logic_error(prefix(path) + "finish() with " + std::to_string(rows_written) + " of " +
                           std::to_string(height) + " rows written");
}

void publish(const std::filesystem::path& partial, const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::rename(partial, path, ec);  // rename(2): atomic replacement within a file system
  if (ec) throw std::runtime_error(prefix(path) + "cannot rename " + partial.string() + " into place: " + ec.message());
}

void discard(const std::filesystem::path& partial) noexcept {
  std::error_code ec;
  std::filesystem::remove(partial, ec);
}

}  // namespace zenith::image::detail
