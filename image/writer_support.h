#pragma once
// Private to zenith_image: what the EXR and PNG writers share — argument checks,
// row bookkeeping and the atomic publication of NAME.partial as NAME.
#include <cstddef>
#include <filesystem>
#include <string>

#include "image/image_writer.h"

namespace zenith::image::detail {

/// NAME.partial next to NAME: the file a writer fills before finish() renames it.
std::filesystem::path partial_path_for(const std::filesystem::path& path);

/// Throws std::invalid_argument unless 1 ≤ width, height ≤ max_side.
void check_dimensions(const std::filesystem::path& path, int width, int height, long long max_side);

/// Throws std::invalid_argument when two attributes share a name.
void check_unique_names(const std::filesystem::path& path, const ImageAttributes& attributes);

/// The checks of ImageWriter::write_rows before anything is written: the writer
/// is still open (std::logic_error otherwise), 0 ≤ row_count and the rows fit
/// (std::logic_error: "rows 10..12 of a 11-row image"), and `value_count` is
/// width · row_count · 3 (std::invalid_argument).
void check_row_block(const std::filesystem::path& path, int width, int height, int rows_written, int row_count,
                     std::size_t value_count, bool open);

/// The checks of ImageWriter::finish(): still open and every row written (std::logic_error).
void check_complete(const std::filesystem::path& path, int height, int rows_written, bool open);

/// Renames `partial` to `path` (replacing an existing file atomically on POSIX);
/// std::runtime_error naming both on failure.
void publish(const std::filesystem::path& partial, const std::filesystem::path& path);

/// Removes `partial` if it exists; never throws (used on abandon).
void discard(const std::filesystem::path& partial) noexcept;

/// "frame.exr: " — the prefix of every message about `path`.
std::string prefix(const std::filesystem::path& path);

}  // namespace zenith::image::detail
