#include "cluster/master/frame_barrier.h"

#include <algorithm>
#include <stdexcept>

namespace zenith::cluster {

void FrameBarrier::start_at(std::uint64_t frame) {
  if (in_flight_) throw std::logic_error("FrameBarrier::start_at with a frame in flight");
  frame_ = frame;
}

std::vector<FrameBarrier::NodeId> FrameBarrier::participants_among(const std::vector<NodeId>& ready) const {
  std::vector<NodeId> participants;
  for (const NodeId node : ready)
    if (!is_lagging(node)) participants.push_back(node);
  return participants;
}

void FrameBarrier::begin(std::uint64_t frame, const std::vector<NodeId>& participants) {
  participants_.clear();
  for (const NodeId node : participants) participants_.emplace(node, false);
  frame_ = frame;
  in_flight_ = true;
}

FrameBarrier::Report FrameBarrier::on_render_done(NodeId node, std::uint64_t frame) {
  if (is_lagging(node)) {
    // Dropped from an earlier barrier: a report of an earlier frame (or any
    // report between frames) brings it back at the next boundary.
    if (frame < frame_ || !in_flight_) {
      lagging_.erase(node);
      return Report::rejoins;
    }
    return Report::ignored_lagging;
  }
  auto it = participants_.find(node);
  if (!in_flight_ || it == participants_.end() || frame != frame_) return Report::ignored;
  it->second = true;
  return Report::counted;
}

std::vector<FrameBarrier::NodeId> FrameBarrier::drop_unfinished() {
  std::vector<NodeId> dropped;
  for (const auto& [node, done] : participants_) {
    if (done) continue;
    lagging_.insert(node);
    dropped.push_back(node);
  }
  std::erase_if(participants_, [](const auto& p) { return !p.second; });
  return dropped;
}

bool FrameBarrier::remove(NodeId node) {
  lagging_.erase(node);
  return in_flight_ && participants_.erase(node) > 0;
}

bool FrameBarrier::complete() const {
  return in_flight_ && std::all_of(participants_.begin(), participants_.end(), [](const auto& p) { return p.second; });
}

FrameBarrier::Release FrameBarrier::release() {
  Release release{frame_, {}};
  for (const auto& [node, done] : participants_) release.present_to.push_back(node);
  participants_.clear();
  in_flight_ = false;
  ++frame_;
  return release;
}

}  // namespace zenith::cluster
