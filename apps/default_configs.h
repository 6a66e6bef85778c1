#pragma once
// The configurations commands fall back on when none is named (docs/cluster.md,
// "The default cluster"): `configs/<name>` under the working directory when it
// exists (a source checkout), otherwise the copy compiled into the binary,
// written with the files it references to a folder of the cache directory, so
// `zenith cluster` works from any directory.
#include <filesystem>
#include <string>

namespace zenith::app {

/// The embedded default cluster: 4 headless nodes, quadrants of a dome master.
inline constexpr const char* kDefaultClusterName = "clusters/local-dome.json";

/// `name` (e.g. kDefaultClusterName) as a file path: ./configs/NAME when it is
/// a regular file, else the embedded copy materialized under
/// <cache>/embedded-configs/<content hash>/NAME. Throws std::runtime_error when
/// neither exists or the copy cannot be written.
std::filesystem::path default_config(const std::string& name);

}  // namespace zenith::app
