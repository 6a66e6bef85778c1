#pragma once
// When a show may start while its later table sets are still being prepared
// (docs/cluster.md, "Shared tables"), as pure logic: no threads, no clock;
// the master reports each set as it is prepared and asks before frame 0.
//
// The sets are prepared one after another in the order of their first frame
// (show/table_plan.h). Frame 0 needs the sets it uses, always. Beyond that:
//  - offline (frames as fast as the barrier allows), nothing: a frame whose
//    set is not there yet waits for it, which costs no more than waiting
//    before frame 0 would have, and the first frames are on disk sooner;
//  - live (frames paced at the show's rate), the show starts only when every
//    set still to prepare is predicted to be ready before its first frame is
//    due, so a live show does not stall halfway. The prediction for a set is
//    the longest preparation measured so far of the same kind (read from the
//    cache, or precomputed), times a safety factor; a kind never measured yet
//    has no prediction, so the show waits until one such set is done.
#include <cstdint>
#include <optional>
#include <vector>

#include "cluster/protocol/messages.h"

namespace zenith::cluster {

/// Invariants: sets() keeps the plan's order; prepared sets stay prepared;
/// may_start() never holds while a set of frame 0 is missing.
class ShowStartRule {
 public:
  struct Set {
    Digest table_hash{};
    std::uint64_t first_frame = 0;  ///< at the show's frame rate
    bool cached = false;            ///< in the master's cache when planned (a read, not a precompute)
    bool prepared = false;
  };

  /// `sets` in the order they are prepared (the plan's: first use); `fps`
  /// the show's frames per second; `paced` live playback; `safety_factor` ≥ 1
  /// multiplies every predicted preparation time.
  ShowStartRule(std::vector<Set> sets, double fps, bool paced, double safety_factor = 1.5);

  /// Set `table_hash` is prepared; it took `seconds`, read from the cache or
  /// precomputed (`from_cache`). Unknown hashes are ignored.
  void prepared(const Digest& table_hash, double seconds, bool from_cache);

  /// Whether frame 0 may start now (the preparation of the remaining sets
  /// begins, at the latest, now).
  bool may_start() const;

  /// Seconds predicted until every remaining set is prepared, counted from
  /// now; nullopt while a kind still to prepare has never been measured.
  std::optional<double> predicted_remaining_s() const;

  const std::vector<Set>& sets() const { return sets_; }

 private:
  std::optional<double> predicted_s(const Set& set) const;

  std::vector<Set> sets_;
  double fps_;
  bool paced_;
  double safety_factor_;
  std::optional<double> longest_cached_s_, longest_computed_s_;
};

}  // namespace zenith::cluster
