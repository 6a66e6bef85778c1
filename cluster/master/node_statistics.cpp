#include "cluster/master/node_statistics.h"

namespace zenith::cluster {

void NodeStatistics::rendered(const std::string& node, double render_ms, bool completed_barrier) {
  Counts& c = counts_[node];
  c.frames_rendered += 1;
  c.last_render_ms = render_ms;
  if (completed_barrier) c.barrier_waits += 1;
}

NodeStatistics::Counts NodeStatistics::of(const std::string& node) const {
  const auto it = counts_.find(node);
  return it == counts_.end() ? Counts{} : it->second;
}

}  // namespace zenith::cluster
