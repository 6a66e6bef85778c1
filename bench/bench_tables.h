#pragma once
// Tables for the frame benchmarks as the `zenith` command obtains them: the
// cache, else the GPU precompute on a context of its own (stored for the next
// run). Shared by render_bench's cases and its --present mode.
#include <fmt/format.h>

#include <chrono>
#include <functional>
#include <string>

#include "atmosphere/lut/precompute_options.h"
#include "atmosphere/lut/table_cache.h"
#include "render/gl/egl_context.h"
#include "render/lut/gpu_precompute.h"
#include "render/renderer.h"

namespace zenith::bench {

/// A TableSource reading `cache` and precomputing (on a headless context made
/// with `context`) what it lacks; `release_current` (when given) detaches the
/// benchmark's own context first (a window's GLX context: EGL refuses to make
/// a context current beside it), `make_current` restores it afterwards. `cache`
/// must outlive the source; `label` names the table sizes in messages ("paper", "small").
inline render::TableSource cached_or_precomputed_tables(const atmosphere::lut::TableCache& cache,
                                                        const atmosphere::lut::PrecomputeOptions& table_options,
                                                        const std::string& label, render::gl::ContextOptions context,
                                                        std::function<void()> make_current,
                                                        std::function<void()> release_current = {}) {
  return
      [&cache, table_options, label, context, make_current, release_current](const atmosphere::AtmosphereModel& model) {
        std::string problem;
        if (auto cached = cache.load(model, table_options, &problem)) {
          fmt::print("tables of '{}' loaded from {}\n", model.name, cache.directory().string());
          return std::move(*cached);
        }
        if (!problem.empty()) fmt::print("ignoring cached tables of '{}': {}\n", model.name, problem);
        fmt::print("precomputing the tables of '{}' ({} sizes, {} orders); stored in {}\n", model.name, label,
                   table_options.max_orders, cache.directory().string());
        atmosphere::lut::PrecomputeOptions o = table_options;
        std::string stage;
        const auto start = std::chrono::steady_clock::now();
        o.progress = [&](const atmosphere::lut::PrecomputeProgress& p) {
          if (p.stage == stage) return;
          stage = p.stage;
          fmt::print(stderr, "  {:6.1f} s  {:3.0f}%  {}\n",
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                     100.0 * p.fraction, p.stage);
        };
        atmosphere::lut::LookupTables t;
        if (release_current) release_current();
        {
          const render::gl::HeadlessContext precompute_context(context);
          t = render::precompute_tables_gpu(model, o, nullptr, &precompute_context);
        }
        make_current();
        try {
          cache.store(model, table_options, t);
        } catch (const std::exception& e) {
          fmt::print(stderr, "could not write the table cache: {}\n", e.what());
        }
        return t;
      };
}

}  // namespace zenith::bench
