#pragma once
// The names a user gives for an atmosphere and for a set of table sizes, on a
// command line (`zenith precompute --atmosphere mars --tables small`) or in a
// config (a cluster's "table_sizes", a show's atmosphere switch), resolved to
// what they name. Shared by the commands (apps/), the cluster and the
// benchmarks; no GL, no table provider.
#include <string>
#include <vector>

#include "atmosphere/lut/precompute_options.h"
#include "atmosphere/lut/table_sizes.h"
#include "atmosphere/parameters.h"

namespace zenith::atmosphere {

/// An atmosphere named by a file path (an existing file, a value with a '/' or
/// ending in ".json") or else by a preset's name. Throws zenith::ConfigError
/// naming the file or listing the presets.
LoadedAtmosphere load_atmosphere_argument(const std::string& value, const LoadOptions& options = {});

/// Table sizes by name (docs/lookup-tables.md, "Named sizes"):
///  - "paper": the defaults (the paper's sizes), 36 MiB a set at 3 wavelengths;
///  - "twilight": the paper's with 128 μs texels instead of 32 (144 MiB), the
///    sun's elevation resolved four times as finely where dusk needs it, and
///    200 samples along the precompute's rays instead of 50 (apply_table_set):
///    the zenith within 3 % of the lit-air reference from sun 0° to −18° at
///    every wavelength, where 64 texels and 50 samples were 4–13 % low below
///    −12° (docs/night-sky.md, "Twilight in the tables"), for 4× the memory
///    and transfer of "paper";
///  - "small": quick tables for tests; "large": every dimension doubled.
/// Throws std::invalid_argument naming the value and the names.
lut::TableSizes table_sizes_by_name(const std::string& name);

/// Sets the sizes and the ray samples of `options` to the named table set's:
/// the sizes of table_sizes_by_name and 200 samples along each scattering ray
/// for "twilight", the default 50 for the others (the day gains nothing from
/// more). Every other option is left as it is. Throws as table_sizes_by_name.
void apply_table_set(const std::string& name, lut::PrecomputeOptions& options);

/// The names table_sizes_by_name knows, for command-line and config checks.
const std::vector<std::string>& table_size_names();

}  // namespace zenith::atmosphere
