#include "cluster/node/link_check_answer.h"

#include <algorithm>
#include <stdexcept>

#include "core/strings.h"

namespace zenith::cluster {

using core::cat;

void LinkCheckAnswer::start(const LinkCheck& check, Clock::time_point now) {
  *this = LinkCheckAnswer{};
  check_ = check;
  pings_until_ = now + std::chrono::milliseconds(check.duration_ms);
}

void LinkCheckAnswer::on_fill(const LinkFill& fill, Clock::time_point now) {
  if (!check_) throw std::runtime_error("LinkFill without a LinkCheck");
  if (fill.index != next_index_)
    throw std::runtime_error(cat("LinkFill ", fill.index, " out of order: expected ", next_index_));
  if (fill_bytes_ + fill.bytes.size() > check_->fill_bytes)
    throw std::runtime_error(
        cat("LinkFill ", fill.index, ": more than the ", check_->fill_bytes, " bytes the LinkCheck named"));
  if (next_index_ == 0) {
    first_fill_ = now;
    pings_until_ = std::min(pings_until_, now);  // the pings would measure the fill's queue
  } else {
    timed_bytes_ += fill.bytes.size();
  }
  ++next_index_;
  fill_bytes_ += fill.bytes.size();
  last_fill_ = now;
}

bool LinkCheckAnswer::complete(Clock::time_point now) const {
  return check_ && now >= pings_until_ && fill_bytes_ == check_->fill_bytes;
}

LinkReport LinkCheckAnswer::report(const PingProbe::Summary& pings, const ClockSync& clock, std::int64_t node_steady_ns,
                                   std::uint64_t node_wall_ns) {
  LinkReport r;
  r.pings_sent = pings.pings;
  r.pongs_received = pings.pongs;
  r.first_ping_ns = pings.first_ping_ns;
  r.last_ping_ns = pings.last_ping_ns;
  r.round_trip_min_ns = pings.round_trip_min_ns;
  r.round_trip_p50_ns = pings.round_trip_p50_ns;
  r.round_trip_p99_ns = pings.round_trip_p99_ns;
  r.round_trip_max_ns = pings.round_trip_max_ns;
  r.node_steady_ns = static_cast<std::uint64_t>(node_steady_ns);
  r.master_steady_ns = static_cast<std::uint64_t>(clock.to_master(node_steady_ns));
  r.node_wall_ns = node_wall_ns;
  r.clock_uncertainty_ns = static_cast<std::uint64_t>(clock.round_trip_ns().value_or(0) / 2);
  r.clock_drift_ppm = std::clamp(clock.drift_ppm(), -1e6, 1e6);
  r.clock_steps = static_cast<std::uint32_t>(std::min<std::uint64_t>(clock.steps(), ~std::uint32_t{0}));
  r.fill_bytes = fill_bytes_;
  r.fill_timed_bytes = timed_bytes_;
  r.fill_ns = static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(last_fill_ - first_fill_).count());
  check_.reset();
  return r;
}

}  // namespace zenith::cluster
