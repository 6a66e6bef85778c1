#include "cluster/master/node_statistics.h"

namespace zenith::cluster {

void NodeStatistics::rendered(const std::string& node, double render_ms, bool completed_barrier) {
  Counts& c = counts_[node];
  c.frames_rendered += 1;
  c.last_render_ms = render_ms;
  if (completed_barrier) c.barrier_waits += 1;
}

std::uint64_t NodeStatistics::presented(const std::string& node, std::uint64_t presents, std::uint64_t late_presents,
                                        double present_ms) {
  PresentBase& b = present_bases_[node];
  if (presents < b.reported_presents || late_presents < b.reported_late) {  // a new process: its counts start at 0
    b.presents += b.reported_presents;
    b.late += b.reported_late;
    b.reported_presents = b.reported_late = 0;
  }
  const std::uint64_t new_late = late_presents - b.reported_late;
  b.reported_presents = presents;
  b.reported_late = late_presents;
  Counts& c = counts_[node];
  c.presents = b.presents + presents;
  c.late_presents = b.late + late_presents;
  if (presents > 0) c.last_present_ms = present_ms;
  return new_late;
}

std::uint64_t NodeStatistics::missed(const std::string& node, std::uint64_t missed_frames) {
  PresentBase& b = present_bases_[node];
  if (missed_frames < b.reported_missed) {  // a new process
    b.missed += b.reported_missed;
    b.reported_missed = 0;
  }
  const std::uint64_t new_missed = missed_frames - b.reported_missed;
  b.reported_missed = missed_frames;
  counts_[node].missed_frames = b.missed + missed_frames;
  return new_missed;
}

NodeStatistics::Counts NodeStatistics::of(const std::string& node) const {
  const auto it = counts_.find(node);
  return it == counts_.end() ? Counts{} : it->second;
}

}  // namespace zenith::cluster
