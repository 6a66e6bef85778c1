#pragma once
// Whole-file reads: the config and warp-file loaders, the offline manifest,
// the benchmarks and the tests read files through these two.
#include <filesystem>
#include <string>

namespace zenith::core {

/// The bytes of a file. Throws std::runtime_error "<path>: cannot open
/// (<reason>)" when it cannot be read, "<path>: is a directory" for a
/// directory and "<path>: read error" when reading fails midway.
std::string file_bytes(const std::filesystem::path& path);

/// The text of a file, or "" when it does not exist or cannot be read: for
/// logs that a test or a benchmark polls while a child process writes them.
std::string read_text(const std::filesystem::path& path);

}  // namespace zenith::core
