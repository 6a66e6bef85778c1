#pragma once
// The names a user gives for an atmosphere and for a set of table sizes, on a
// command line (`zenith precompute --atmosphere mars --tables small`) or in a
// config (a cluster's "table_sizes", a show's atmosphere switch), resolved to
// what they name. Shared by the commands (apps/), the cluster and the
// benchmarks; no GL, no table provider.
#include <string>
#include <vector>

#include "atmosphere/lut/table_sizes.h"
#include "atmosphere/parameters.h"

namespace zenith::atmosphere {

/// An atmosphere named by a file path (an existing file, a value with a '/' or
/// ending in ".json") or else by a preset's name. Throws zenith::ConfigError
/// naming the file or listing the presets.
LoadedAtmosphere load_atmosphere_argument(const std::string& value, const LoadOptions& options = {});

/// Table sizes by name (docs/lookup-tables.md, "Named sizes"):
///  - "paper": the defaults (the paper's sizes), 36 MiB a set at 3 wavelengths;
///  - "twilight": the paper's with 64 μs texels instead of 32 (72 MiB): the
///    sun's elevation resolved twice as finely where dusk needs it — the
///    zenith's error against the path tracer at sun −3° falls from 4.5 % to
///    1.6 % and the −15° to −18° zenith converges (docs/night-sky.md,
///    "Twilight in the tables"), for twice the precompute, memory and transfer;
///  - "small": quick tables for tests; "large": every dimension doubled.
/// Throws std::invalid_argument naming the value and the names.
lut::TableSizes table_sizes_by_name(const std::string& name);

/// The names table_sizes_by_name knows, for command-line and config checks.
const std::vector<std::string>& table_size_names();

}  // namespace zenith::atmosphere
