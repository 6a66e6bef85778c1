#include "cluster/master/frame_pacer.h"

#include <cmath>
#include <stdexcept>

#include "core/strings.h"

namespace zenith::cluster {

namespace {
double checked_rate(double rate_hz) {
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0))
    throw std::invalid_argument(core::cat("frame pacer: rate ", rate_hz, " Hz must be > 0"));
  return rate_hz;
}
}  // namespace

FramePacer::FramePacer(double rate_hz)
    : rate_hz_(checked_rate(rate_hz)),
      period_(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate_hz_))) {}

void FramePacer::start(Clock::time_point t0) { t0_ = t0; }

FramePacer::Clock::time_point FramePacer::due(std::uint64_t n) const {
  // n / rate in double, not n · period: the period rounded to the clock's tick
  // would drift by up to a tick per frame.
  return t0_ +
         std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(static_cast<double>(n) / rate_hz_));
}

FramePacer::Clock::duration FramePacer::wait_before(std::uint64_t n, Clock::time_point now) {
  const Clock::time_point when = due(n);
  if (now <= when) return when - now;
  if (now - when > period_) {  // fell behind: frame n is due now, the later ones a period apart
    t0_ += now - when;
    ++slips_;
  }
  return Clock::duration::zero();
}

}  // namespace zenith::cluster
