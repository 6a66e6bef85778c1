#pragma once
// Obtains the lookup tables of an atmosphere: from the cache when a valid set
// with the same key exists, else by precomputing (GPU by default, CPU on
// request or when no GL context can be had) and storing them.
#include <filesystem>
#include <optional>
#include <string>

#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/lut/precompute_options.h"
#include "atmosphere/named_inputs.h"
#include "atmosphere/parameters.h"

namespace zenith::render {

enum class PrecomputeBackend { Gpu, Cpu };

struct TableRequest {
  atmosphere::lut::PrecomputeOptions options;
  PrecomputeBackend backend = PrecomputeBackend::Gpu;
  std::optional<std::filesystem::path> cache_directory;  ///< default: default_cache_directory()
  bool use_cache = true;
  bool show_progress = true;
};

struct ObtainedTables {
  atmosphere::lut::LookupTables tables;
  atmosphere::lut::PrecomputeReport report;  ///< empty stages when loaded from the cache
  bool from_cache = false;
  std::filesystem::path cache_file;
};

ObtainedTables obtain_tables(const atmosphere::AtmosphereModel& model, const TableRequest& request);

// Naming an atmosphere or a set of table sizes (command lines, configs) is
// atmosphere/named_inputs.h's. These two names stay here only until cluster/
// calls them there (issue 27's cluster split); new code includes that header.
using atmosphere::load_atmosphere_argument;
using atmosphere::table_sizes_by_name;

}  // namespace zenith::render
