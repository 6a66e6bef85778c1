#pragma once
// Small lookup tables computed once per preset and shared by every test: in
// memory within a process and, because CTest runs each test in a process of its
// own, through a table cache in the build tree (ZENITH_TEST_TABLE_CACHE): the
// first test to need a preset computes it (seconds), the others load it (ms).
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "atmosphere/lut/cpu_precompute.h"
#include "atmosphere/lut/table_cache.h"
#include "atmosphere/parameters.h"

namespace zenith::atmosphere::lut {

struct SmallTables {
  AtmosphereModel model;
  PrecomputeOptions options;
  PrecomputeReport report;
  LookupTables tables;
  std::unique_ptr<TableQueries> queries;

  /// Options of the shared small tables: small sizes, 4 orders and nothing
  /// after them (no series tail: the bounds of the tests that use them were
  /// measured so), coarse sphere integral.
  static PrecomputeOptions small_options() {
    PrecomputeOptions o;
    o.sizes = TableSizes::small();
    o.max_orders = 4;
    o.series_tail = false;
    o.sphere_zenith_samples = 8;
    return o;
  }
  /// The same sizes with the project's default orders and their series tail.
  static PrecomputeOptions default_orders_options() {
    PrecomputeOptions o = small_options();
    o.max_orders = kDefaultScatteringOrders;
    o.series_tail = true;
    return o;
  }

  /// The shared tables (from the build tree's cache when another test made them:
  /// `report` is then empty).
  static const SmallTables& get(const std::string& preset) { return instance(preset, false, false); }
  /// The shared tables computed in this process, so `report` is filled.
  static const SmallTables& computed(const std::string& preset) { return instance(preset, true, false); }
  /// Small tables with the default orders and the series tail (default_orders_options).
  static const SmallTables& with_default_orders(const std::string& preset) { return instance(preset, false, true); }

 private:
  static const SmallTables& instance(const std::string& preset, bool need_report, bool default_orders) {
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<SmallTables>> cache;
    std::lock_guard lock(mutex);
    auto& slot = cache[preset + (default_orders ? " default orders" : "")];
    if (!slot || (need_report && slot->report.stages.empty())) {
      slot = std::make_unique<SmallTables>();
      slot->model = load_preset(preset).model;
      slot->options = default_orders ? default_orders_options() : small_options();
#ifdef ZENITH_TEST_TABLE_CACHE
      const TableCache disk(ZENITH_TEST_TABLE_CACHE);
      std::optional<LookupTables> stored;
      if (!need_report) stored = disk.load(slot->model, slot->options);
      if (stored) {
        slot->tables = std::move(*stored);
      } else {
        slot->tables = precompute_tables_cpu(slot->model, slot->options, &slot->report);
        disk.store(slot->model, slot->options, slot->tables);  // atomic: parallel tests may race
      }
#else
      slot->tables = precompute_tables_cpu(slot->model, slot->options, &slot->report);
#endif
      slot->queries = std::make_unique<TableQueries>(slot->model, slot->tables);
    }
    return *slot;
  }
};

}  // namespace zenith::atmosphere::lut
