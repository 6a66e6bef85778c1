// `zenith precompute`: compute (or load) an atmosphere's lookup tables, showing
// progress, the time of each stage, the orders used and the table-set hash.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "apps/commands.h"
#include "atmosphere/lut/table_cache.h"
#include "atmosphere/model_hash.h"
#include "atmosphere/named_inputs.h"
#include "offline/output_rendering.h"
#include "render/lut/table_provider.h"

namespace zenith::app {
namespace {

struct PrecomputeArgs {
  std::string atmosphere, out_dir, tables = "paper", cache_dir;
  bool cpu = false, no_cache = false, no_series_tail = false, serial_compile = false, compile_contexts = false;
  int orders = atmosphere::lut::kDefaultScatteringOrders;
  double tolerance = 0.0;
  unsigned threads = 0;
};

void run_precompute(const PrecomputeArgs& a) {
  const auto loaded = atmosphere::load_atmosphere_argument(a.atmosphere);
  render::TableRequest request = make_table_request(a.tables, a.orders, a.cpu, !a.no_cache, a.cache_dir);
  request.options.tolerance = a.tolerance;
  request.options.series_tail = !a.no_series_tail;
  request.options.threads = a.threads;
  if (a.serial_compile) request.compile = render::gl::CompileMode::serial;
  if (a.compile_contexts) request.compile = render::gl::CompileMode::contexts;

  const render::ObtainedTables t = render::obtain_tables(loaded.model, request);
  fmt::print("atmosphere      {}\n", loaded.model.name);
  fmt::print("lut hash        {}\n", atmosphere::lookup_table_hash(loaded.model));
  fmt::print("table set key   {}\n", atmosphere::lut::table_set_key(loaded.model, request.options));
  fmt::print("table sizes     {}\n", t.tables.sizes.describe());
  if (t.from_cache) {
    fmt::print("source          cache ({})\n", t.cache_file.string());
  } else {
    fmt::print("source          computed on {}\n", t.report.device);
    for (const auto& s : t.report.stages) fmt::print("  {:<36} {:8.3f} s\n", s.stage, s.seconds);
    fmt::print("  {:<36} {:8.3f} s\n", "total", t.report.total_seconds());
    std::string fractions;
    for (std::size_t i = 0; i < t.report.order_fraction.size(); ++i)
      fractions += fmt::format("{}{}: {:.4f}", i ? ", " : "", i + 1, t.report.order_fraction[i]);
    if (t.report.tail_fraction > 0.0)
      fractions +=
          fmt::format(", orders {}–∞ as the series tail: {:.4f}", t.report.orders_used + 1, t.report.tail_fraction);
    fmt::print("orders used     {} (share of in-scattered radiance per order: {})\n", t.report.orders_used, fractions);
    if (!t.cache_file.empty()) fmt::print("cached in       {}\n", t.cache_file.string());
  }
  if (!a.out_dir.empty()) {
    std::filesystem::create_directories(a.out_dir);
    const auto path = std::filesystem::path(a.out_dir) /
                      fmt::format("tables-{}.exr", atmosphere::lookup_table_hash(loaded.model).substr(0, 16));
    atmosphere::lut::write_tables_exr(path, loaded.model, atmosphere::lut::table_set_key(loaded.model, request.options),
                                      t.tables);
    fmt::print("written         {}\n", path.string());
  }
}

}  // namespace

void register_precompute_command(CLI::App& app) {
  auto args = std::make_shared<PrecomputeArgs>();
  CLI::App* cmd = app.add_subcommand("precompute", "Compute (or load from the cache) an atmosphere's lookup tables");
  cmd->add_option("--atmosphere", args->atmosphere, "Preset name or atmosphere JSON file")->required();
  cmd->add_option("--out", args->out_dir, "Also write the table set as OpenEXR into this directory");
  cmd->add_flag("--cpu", args->cpu, "Use the CPU implementation instead of the GPU one");
  auto* orders = cmd->add_option("--orders", args->orders, "Scattering orders n")->check(CLI::Range(1, 50));
  auto* tol = cmd->add_option("--tolerance", args->tolerance,
                              "Stop when an order adds less than this fraction of the total (caps at 50 orders)")
                  ->check(CLI::Range(1e-9, 1.0));
  orders->excludes(tol);
  cmd->add_flag("--no-series-tail", args->no_series_tail,
                "Drop the orders after the last one instead of adding their geometric tail");
  cmd->add_option("--tables", args->tables,
                  "Table sizes: paper (default), twilight (128 mu_s texels and 200 ray samples, for dusk and night), "
                  "small, large")
      ->check(CLI::IsMember(atmosphere::table_size_names()));
  cmd->add_option("--cache", args->cache_dir, "Cache directory (default $XDG_CACHE_HOME/zenith)");
  cmd->add_flag("--no-cache", args->no_cache, "Neither read nor write the cache");
  cmd->add_option("--threads", args->threads, "CPU threads (default: all)");
  auto* serial = cmd->add_flag("--serial-compile", args->serial_compile,
                               "Build the GPU programs one at a time where first used, instead of starting them all "
                               "at once on the driver's compiler threads (to compare; --log-level debug prints what "
                               "the builds took)");
  cmd->add_flag("--compile-contexts", args->compile_contexts,
                "Build the GPU programs all at once, each on a thread with a GL context of its own, instead of on "
                "the driver's compiler threads (to compare)")
      ->excludes(serial);
  cmd->callback([args, tol] {
    PrecomputeArgs a = *args;
    if (tol->count() > 0) a.orders = 50;
    run_precompute(a);
  });
}

}  // namespace zenith::app
