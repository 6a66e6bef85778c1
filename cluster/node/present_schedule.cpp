#include "cluster/node/present_schedule.h"

#include <algorithm>

namespace zenith::cluster {

PresentSchedule::Arrival PresentSchedule::on_frame(const FrameState& state, Clock::time_point present_at,
                                                   Clock::time_point now) {
  const std::uint64_t frame = state.frame;
  if (pending_.count(frame) || (current_ && current_->frame == frame) || last_presented_ == frame)
    return Arrival::duplicate;
  if (last_presented_ && frame < *last_presented_) return Arrival::stale;
  if (present_at <= now) return Arrival::late;
  if (current_ && frame < current_->frame) {
    // An earlier frame came after the node moved on to a later one (its
    // first copies were lost; its last copy leaves the master one period
    // before its moment, just when the frame before it is presented): it is
    // still in time, so it goes first and the later one is rendered again
    // after it.
    pending_.emplace(current_->frame, Pending{std::move(current_->state), current_->present_at});
    current_.reset();
  }
  pending_.emplace(frame, Pending{state, present_at});
  return Arrival::taken;
}

std::optional<PresentSchedule::Step> PresentSchedule::next(Clock::time_point now) {
  if (current_) {
    if (now + handoff_ < current_->present_at) return std::nullopt;
    Step present{Step::Kind::present, current_->frame, {}, current_->present_at};
    // Frames between the last presented and this one never reached the screen.
    if (last_presented_ && present.frame > *last_presented_ + 1) missed_ += present.frame - *last_presented_ - 1;
    last_presented_ = present.frame;
    ++presented_;
    current_.reset();
    return present;
  }
  // The next frame whose moment is still ahead; those whose moment passed
  // while they waited are dropped (missed: counted by the gap at the next present).
  while (!pending_.empty()) {
    auto first = pending_.begin();
    if (first->second.present_at > now) {
      current_ = Step{Step::Kind::render, first->first, std::move(first->second.state), first->second.present_at};
      pending_.erase(first);
      return current_;
    }
    pending_.erase(first);
  }
  return std::nullopt;
}

std::optional<PresentSchedule::Clock::time_point> PresentSchedule::wake_at() const {
  if (current_) return current_->present_at - handoff_;
  return std::nullopt;
}

PresentSchedule::Clock::duration present_handoff(double frame_rate_hz) {
  using Duration = PresentSchedule::Clock::duration;
  const auto half_period = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(0.5 / frame_rate_hz));
  return std::min<Duration>(std::chrono::milliseconds(4), half_period);
}

bool drop_frame_behind(std::optional<PresentSchedule::Clock::time_point> later_moment,
                       PresentSchedule::Clock::time_point now) {
  return !later_moment || *later_moment <= now;
}

const char* to_string(PresentSchedule::Arrival arrival) {
  switch (arrival) {
    case PresentSchedule::Arrival::taken: return "taken";
    case PresentSchedule::Arrival::duplicate: return "duplicate";
    case PresentSchedule::Arrival::stale: return "stale";
    case PresentSchedule::Arrival::late: return "late";
  }
  return "?";
}

}  // namespace zenith::cluster
