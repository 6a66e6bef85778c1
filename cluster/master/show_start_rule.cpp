#include "cluster/master/show_start_rule.h"

#include <algorithm>
#include <stdexcept>

namespace zenith::cluster {

ShowStartRule::ShowStartRule(std::vector<Set> sets, double fps, bool paced, double safety_factor)
    : sets_(std::move(sets)), fps_(fps), paced_(paced), safety_factor_(safety_factor) {
  if (!(fps_ > 0.0)) throw std::invalid_argument("ShowStartRule: the frame rate must be positive");
  if (!(safety_factor_ >= 1.0)) throw std::invalid_argument("ShowStartRule: the safety factor must be at least 1");
}

void ShowStartRule::prepared(const Digest& table_hash, double seconds, bool from_cache) {
  std::optional<double>& longest = from_cache ? longest_cached_s_ : longest_computed_s_;
  longest = std::max(longest.value_or(0.0), seconds);
  for (Set& set : sets_)
    if (set.table_hash == table_hash) set.prepared = true;
}

std::optional<double> ShowStartRule::predicted_s(const Set& set) const {
  const std::optional<double>& longest = set.cached ? longest_cached_s_ : longest_computed_s_;
  if (!longest) return std::nullopt;
  return *longest * safety_factor_;
}

std::optional<double> ShowStartRule::predicted_remaining_s() const {
  double total = 0.0;
  for (const Set& set : sets_) {
    if (set.prepared) continue;
    const std::optional<double> seconds = predicted_s(set);
    if (!seconds) return std::nullopt;
    total += *seconds;
  }
  return total;
}

bool ShowStartRule::may_start() const {
  for (const Set& set : sets_)
    if (set.first_frame == 0 && !set.prepared) return false;
  if (!paced_) return true;
  // Sets are prepared in this order, one at a time: the k-th remaining set is
  // ready after the predicted times of the remaining sets up to it. Each must
  // be ready when its first frame is due (first_frame / fps after frame 0).
  double ready_at_s = 0.0;
  for (const Set& set : sets_) {
    if (set.prepared) continue;
    const std::optional<double> seconds = predicted_s(set);
    if (!seconds) return false;
    ready_at_s += *seconds;
    if (ready_at_s > static_cast<double>(set.first_frame) / fps_) return false;
  }
  return true;
}

}  // namespace zenith::cluster
