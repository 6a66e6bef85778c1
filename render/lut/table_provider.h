#pragma once
// Obtains the lookup tables of an atmosphere: from the cache when a valid set
// with the same key exists, else by precomputing (GPU by default, CPU on
// request or when no GL context can be had) and storing them.
#include <filesystem>
#include <optional>
#include <string>

#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/lut/precompute_options.h"
#include "atmosphere/parameters.h"
#include "render/gl/shader_build.h"

namespace zenith::render {

enum class PrecomputeBackend { Gpu, Cpu };

struct TableRequest {
  atmosphere::lut::PrecomputeOptions options;
  PrecomputeBackend backend = PrecomputeBackend::Gpu;
  std::optional<std::filesystem::path> cache_directory;  ///< default: default_cache_directory()
  bool use_cache = true;
  bool show_progress = true;
  /// The GPU precompute's programs: all started at once (parallel), or one at a time.
  gl::CompileMode compile = gl::CompileMode::parallel;
};

struct ObtainedTables {
  atmosphere::lut::LookupTables tables;
  atmosphere::lut::PrecomputeReport report;  ///< empty stages when loaded from the cache
  bool from_cache = false;
  std::filesystem::path cache_file;
};

ObtainedTables obtain_tables(const atmosphere::AtmosphereModel& model, const TableRequest& request);

/// The directory the request's cache lives in (its own or
/// default_cache_directory()); empty where it uses none. The renderer keeps
/// its generated albedo maps there too (RenderOptions::albedo_cache_directory).
std::filesystem::path cache_directory_of(const TableRequest& request);
/// Where the request's linked programs are kept (render/gl/program_binary_cache.h):
/// the "programs" folder of its cache, the precompute's and the renderer's
/// (RenderOptions::program_cache_directory); empty where it uses no cache.
std::filesystem::path program_cache_directory_of(const TableRequest& request);

}  // namespace zenith::render
