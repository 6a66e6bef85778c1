#include "cluster/link/local_clock.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace zenith::cluster {

namespace {
std::int64_t ns_of(LocalClock::Steady::time_point s) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(s.time_since_epoch()).count();
}
}  // namespace

LocalClock::LocalClock(const Faults& faults, Steady::time_point origin) : faults_(faults), origin_ns_(ns_of(origin)) {}

bool LocalClock::jumped(std::int64_t since_origin_ns) const {
  if (!faults_.steps() || since_origin_ns < 0) return false;
  return (since_origin_ns / faults_.step_every.count()) % 2 == 1;
}

std::int64_t LocalClock::read_ns(Steady::time_point s) const {
  const std::int64_t steady_ns = ns_of(s);
  if (!faults_.any()) return steady_ns;
  const std::int64_t u = steady_ns - origin_ns_;
  const auto drift = static_cast<std::int64_t>(std::llround(faults_.drift_ppm * 1e-6 * static_cast<double>(u)));
  return steady_ns + drift + (jumped(u) ? faults_.step_ns : 0);
}

LocalClock::Steady::time_point LocalClock::steady_at(std::int64_t local_ns) const {
  if (!faults_.any()) return Steady::time_point(std::chrono::nanoseconds(local_ns));
  // Within one interval of the jump the clock is a line of slope 1 + drift,
  // so the moment it reads local_ns is one of: the crossing without the jump
  // (u0), the crossing with it (u1), or the start of an interval, where the
  // clock jumps ahead over local_ns. Of those that read local_ns or later,
  // the first; nothing earlier can (before min(u0, u1) the clock reads less
  // whatever the jump).
  const double rate = 1.0 + faults_.drift_ppm * 1e-6;
  const double target = static_cast<double>(local_ns - origin_ns_);
  // Two nanoseconds early: the drift's rounding puts the true crossing within
  // half a nanosecond of the estimate, and the search below steps forward.
  const auto u0 = static_cast<std::int64_t>(std::floor(target / rate)) - 2;
  const auto u1 = static_cast<std::int64_t>(std::floor((target - static_cast<double>(faults_.step_ns)) / rate)) - 2;
  std::int64_t candidates[4] = {u0, u1, u0, u1};
  if (faults_.steps()) {
    const std::int64_t every = faults_.step_every.count();
    const std::int64_t earliest = std::max<std::int64_t>(std::min(u0, u1), 0);
    const std::int64_t start = (earliest + every - 1) / every * every;  // the first interval start at or after it
    candidates[2] = start;
    candidates[3] = start + every;
  }
  std::optional<std::int64_t> first;
  for (std::int64_t u : candidates) {
    // Forward to the first nanosecond that reads local_ns (within the
    // interval the candidate lies in, the clock rises by 1 or 2 ns a ns).
    for (int nudge = 0; nudge < 5 && read_ns(Steady::time_point(std::chrono::nanoseconds(origin_ns_ + u))) < local_ns;
         ++nudge)
      ++u;
    if (read_ns(Steady::time_point(std::chrono::nanoseconds(origin_ns_ + u))) >= local_ns && (!first || u < *first))
      first = u;
  }
  return Steady::time_point(std::chrono::nanoseconds(origin_ns_ + first.value_or(u0)));
}

}  // namespace zenith::cluster
