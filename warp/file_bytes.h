#pragma once
// Whole-file reads for the warp-file loaders (meshes, PFM, MPCDI).
#include <filesystem>
#include <string>

namespace zenith::warp {

/// The bytes of a file. Throws std::runtime_error "<path>: cannot open (<reason>)"
/// when it cannot be read, and "<path>: is a directory" for a directory.
std::string read_file_bytes(const std::filesystem::path& path);

}  // namespace zenith::warp
