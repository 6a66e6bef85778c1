#include "render/lut/table_provider.h"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <optional>

#include "atmosphere/lut/cpu_precompute.h"
#include "atmosphere/lut/table_cache.h"
#include "core/progress_bar.h"
#include "render/gl/egl_context.h"
#include "render/gl/shader_program.h"
#include "render/lut/gpu_precompute.h"

namespace zenith::render {

using namespace atmosphere::lut;

ObtainedTables obtain_tables(const atmosphere::AtmosphereModel& model, const TableRequest& request) {
  const TableCache cache(request.cache_directory.value_or(default_cache_directory()));
  ObtainedTables out;
  if (request.use_cache) {
    std::string problem;
    if (auto cached = cache.load(model, request.options, &problem)) {
      out.tables = std::move(*cached);
      out.from_cache = true;
      out.cache_file = cache.path_for(table_set_key(model, request.options));
      spdlog::info("lookup tables loaded from {}", out.cache_file.string());
      return out;
    }
    if (!problem.empty()) spdlog::warn("ignoring cached tables: {}; recomputing", problem);
  }

  // The GPU path needs a GL context; without one (no EGL, no llvmpipe) use the CPU.
  std::optional<render::gl::HeadlessContext> context;
  if (request.backend == PrecomputeBackend::Gpu) {
    try {
      context.emplace();
    } catch (const std::exception& e) {
      spdlog::warn("no GL context for the GPU precompute, using the CPU: {}", e.what());
    }
  }

  PrecomputeOptions options = request.options;
  std::optional<core::ProgressBar> bar;
  if (request.show_progress) {
    bar.emplace("precompute");
    options.progress = [&bar, caller = request.options.progress](const PrecomputeProgress& p) {
      bar->update(p.stage, p.fraction);
      if (caller) caller(p);  // the caller's own callback (the master's cancellation) still runs
    };
  }
  bool gpu_done = false;
  if (context) {
    spdlog::debug("precomputing on {} ({})", context->renderer(), context->source());
    try {
      // The linked programs beside the tables: a warm run skips compiling them.
      std::optional<std::filesystem::path> programs;
      if (request.use_cache) programs = program_cache_directory_of(request);
      out.tables = render::precompute_tables_gpu(model, options, &out.report, &*context, GpuPrecision::automatic,
                                                 programs, request.compile);
      gpu_done = true;
    } catch (const gl::ShaderBuildError& e) {
      // A driver that refuses one of the precompute's programs must not stop a
      // show: the CPU computes the same tables (slower). One warning, naming the
      // program and the driver, with the driver's first message.
      const std::string what = e.what();
      std::string first = what.substr(what.find('\n') == std::string::npos ? 0 : what.find('\n') + 1);
      first = first.substr(0, first.find('\n'));
      if (bar) bar->finish();
      spdlog::warn(
          "GPU precompute: shader program '{}' does not build on this driver (GL_VENDOR '{}', GL_RENDERER "
          "'{}', GL_VERSION '{}'): {}; precomputing on the CPU instead",
          e.program(), context->vendor(), context->renderer(), context->version(), first);
      out.report = {};
      if (bar) bar.emplace("precompute (CPU)");
    }
  }
  if (!gpu_done) out.tables = precompute_tables_cpu(model, options, &out.report);
  if (bar) bar->finish();
  if (request.use_cache) {
    try {
      out.cache_file = cache.store(model, request.options, out.tables);
    } catch (const std::exception& e) {
      spdlog::warn("could not write the table cache in {}: {}", cache.directory().string(), e.what());
    }
  }
  return out;
}

std::filesystem::path cache_directory_of(const TableRequest& request) {
  if (!request.use_cache) return {};
  return request.cache_directory.value_or(atmosphere::lut::default_cache_directory());
}

std::filesystem::path program_cache_directory_of(const TableRequest& request) {
  const std::filesystem::path tables = cache_directory_of(request);
  return tables.empty() ? tables : tables / "programs";
}

}  // namespace zenith::render
