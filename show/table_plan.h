#pragma once
// How many lookup-table sets a show needs and what they cost (docs/shows.md,
// "Table sets"), reported before playback or an offline render, and the
// precompute of the missing ones ahead of the first frame.
#include <cstdint>
#include <string>
#include <vector>

#include "atmosphere/lut/precompute_options.h"
#include "atmosphere/lut/table_cache.h"
#include "show/show.h"

namespace zenith::show {

struct TablePlanEntry {
  AtmosphereVersion version;
  std::uint64_t first_frame = 0;  ///< first frame (at the plan's fps) that uses it
  std::uint64_t frames = 0;       ///< frames that use it
  bool cached = false;            ///< a valid set is in the cache already
  std::uint64_t bytes = 0;        ///< size of the set (float32 texels of every table)
};

struct TablePlan {
  double fps = 0.0;
  std::uint64_t frame_count = 0;
  std::vector<TablePlanEntry> sets;  ///< in order of first use
  std::size_t missing() const;       ///< sets to precompute
  std::uint64_t total_bytes() const;
};

/// Samples every frame of `show` at `fps` and lists the table sets it uses.
TablePlan plan_tables(const Show& show, double fps, const atmosphere::lut::PrecomputeOptions& options,
                      const atmosphere::lut::TableCache& cache);

/// What the sets may take before `show plan` or `show render` warns: their
/// total size (each is held whole by the master and every node cache), 4 GiB
/// unless --table-budget-gib says otherwise.
inline constexpr double kDefaultTableBudgetGiB = 4.0;
/// "warning: …" when the plan's sets together exceed `budget_gib`, naming
/// their count and size; "" otherwise. Said before anything is precomputed.
std::string budget_warning(const TablePlan& plan, double budget_gib);

/// A human-readable report: one line per set (body, first parameter values
/// that differ from the scene's, first frame, frames, cached or to compute,
/// MiB), then the totals and, when `seconds_per_set` > 0, the estimated
/// precompute time.
std::string describe(const TablePlan& plan, double seconds_per_set = 0.0);

}  // namespace zenith::show
