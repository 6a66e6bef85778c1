#pragma once
// The names a user gives for an atmosphere and for a set of table sizes, on a
// command line (`zenith precompute --atmosphere mars --tables small`) or in a
// config (a cluster's "table_sizes", a show's atmosphere switch), resolved to
// what they name. Shared by the commands (apps/), the cluster and the
// benchmarks; no GL, no table provider.
#include <string>

#include "atmosphere/lut/table_sizes.h"
#include "atmosphere/parameters.h"

namespace zenith::atmosphere {

/// An atmosphere named by a file path (an existing file, a value with a '/' or
/// ending in ".json") or else by a preset's name. Throws zenith::ConfigError
/// naming the file or listing the presets.
LoadedAtmosphere load_atmosphere_argument(const std::string& value, const LoadOptions& options = {});

/// Table sizes by name: "paper" (the defaults), "small" (tests), "large".
/// Throws std::invalid_argument naming the value and the three names.
lut::TableSizes table_sizes_by_name(const std::string& name);

}  // namespace zenith::atmosphere
