#pragma once
// Elapsed time on the steady clock since an instant: durations in log lines
// and reports, and the cluster's timeouts (silence, handshake, barrier).
#include <chrono>

namespace zenith::core {

using SteadyClock = std::chrono::steady_clock;

/// Milliseconds since `start`.
inline double ms_since(SteadyClock::time_point start) {
  return std::chrono::duration<double, std::milli>(SteadyClock::now() - start).count();
}
/// Milliseconds from `start` to `end` (negative when `end` comes first).
inline double ms_between(SteadyClock::time_point start, SteadyClock::time_point end) {
  return std::chrono::duration<double, std::milli>(end - start).count();
}
/// Seconds since `start`.
inline double seconds_since(SteadyClock::time_point start) {
  return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

}  // namespace zenith::core
