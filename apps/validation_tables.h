#pragma once
// The tables `zenith validate` asks for (validate/validation_tables.h), from
// the table request its command line built: the cache, else a precompute on
// the GPU or the CPU (render/lut/table_provider.h).
#include <memory>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "apps/cli_options.h"
#include "offline/output_rendering.h"
#include "render/lut/table_provider.h"
#include "validate/validation_tables.h"

namespace zenith::app {

/// Where the tables of a `zenith validate` check come from, as its command
/// line says (--tables, --orders, --cache, --cpu, --no-cache, --threads).
struct ValidationTableArgs {
  std::string cache_dir;
  int orders = atmosphere::lut::kDefaultScatteringOrders;
  unsigned threads = 0;
  bool cpu = false, no_cache = false;

  /// The request for tables of the sizes named `table_sizes`.
  render::TableRequest request(const std::string& table_sizes) const {
    render::TableRequest r = make_table_request(table_sizes, orders, cpu, !no_cache, cache_dir);
    r.options.threads = threads;
    return r;
  }
};

/// The options of ValidationTableArgs, the sizes into `table_sizes`.
inline void add_validation_table_options(CLI::App* cmd, std::string& table_sizes, ValidationTableArgs& args) {
  add_table_options(cmd, table_sizes, args.orders, args.cache_dir);
  cmd->add_flag("--cpu", args.cpu, "Precompute on the CPU instead of the GPU (when not cached)");
  cmd->add_flag("--no-cache", args.no_cache, "Neither read nor write the table cache");
  cmd->add_option("--threads", args.threads, "CPU threads (default: all)");
}

inline validate::TablesFor validation_tables(render::TableRequest request) {
  return [request = std::move(request)](const atmosphere::AtmosphereModel& model) {
    render::ObtainedTables t = render::obtain_tables(model, request);
    return validate::ValidationTables{std::move(t.tables),
                                      t.from_cache ? std::string("cache") : "computed on " + t.report.device};
  };
}

/// What a `zenith validate` check's command line sets: the check's own
/// options and where its tables come from.
template <class Options>
struct ValidationArgs {
  Options validation;
  ValidationTableArgs tables;
};

/// Adds the check `validate NAME` with the options every check has (--out,
/// the table options, --no-plots); on a parsed command line it calls
/// `check(options, tables)`. The check's own options are added to the
/// returned command, into the returned args.
template <class Options, class Check>
std::pair<CLI::App*, std::shared_ptr<ValidationArgs<Options>>> add_validation_check(CLI::App& validate,
                                                                                    const std::string& name,
                                                                                    const std::string& description,
                                                                                    Check check) {
  auto args = std::make_shared<ValidationArgs<Options>>();
  CLI::App* cmd = validate.add_subcommand(name, description);
  cmd->add_option("--out", args->validation.out_dir, "Output directory (CSV, gnuplot scripts, PNG)")
      ->capture_default_str();
  add_validation_table_options(cmd, args->validation.tables, args->tables);
  cmd->add_flag("--no-plots", args->validation.no_plots, "Write the data but no gnuplot scripts or PNG");
  cmd->callback(
      [args, check] { check(args->validation, validation_tables(args->tables.request(args->validation.tables))); });
  return {cmd, args};
}

}  // namespace zenith::app
