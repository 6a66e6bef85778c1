#pragma once
// Small lookup tables computed once per test process and preset (the CPU
// precompute of small tables takes a few seconds; every LUT test shares them).
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "atmosphere/lut/cpu_precompute.h"
#include "atmosphere/parameters.h"

namespace zenith::atmosphere::lut {

struct SmallTables {
  AtmosphereModel model;
  PrecomputeOptions options;
  PrecomputeReport report;
  LookupTables tables;
  std::unique_ptr<TableQueries> queries;

  /// Options of the shared small tables: small sizes, 4 orders, coarse sphere integral.
  static PrecomputeOptions small_options() {
    PrecomputeOptions o;
    o.sizes = TableSizes::small();
    o.max_orders = 4;
    o.sphere_zenith_samples = 8;
    return o;
  }

  static const SmallTables& get(const std::string& preset) {
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<SmallTables>> cache;
    std::lock_guard lock(mutex);
    auto& slot = cache[preset];
    if (!slot) {
      slot = std::make_unique<SmallTables>();
      slot->model = load_preset(preset).model;
      slot->options = small_options();
      slot->tables = precompute_tables_cpu(slot->model, slot->options, &slot->report);
      slot->queries = std::make_unique<TableQueries>(slot->model, slot->tables);
    }
    return *slot;
  }
};

}  // namespace zenith::atmosphere::lut
