#pragma once
// The wall clock and the steady clock read at one moment. Two calls in a row
// are two moments: a thread preempted between them on a loaded machine pairs
// a wall time with a steady time milliseconds apart. So the wall clock is
// read between two steady readings, and of a few tries the pair with the
// tightest bracket is kept (the steady time is the bracket's midpoint).
#include <chrono>
#include <cstdint>

namespace zenith::core {

struct WallAtSteady {
  std::int64_t steady_ns = 0;   ///< std::chrono::steady_clock, since its epoch
  std::int64_t wall_ns = 0;     ///< std::chrono::system_clock, since 1970
  std::int64_t bracket_ns = 0;  ///< the two steady readings' distance: the pairing's uncertainty
};

inline WallAtSteady wall_at_steady(int tries = 5) {
  const auto ns = [](auto d) { return std::chrono::duration_cast<std::chrono::nanoseconds>(d).count(); };
  WallAtSteady best{0, 0, -1};
  for (int k = 0; k < tries; ++k) {
    const std::int64_t before = ns(std::chrono::steady_clock::now().time_since_epoch());
    const std::int64_t wall = ns(std::chrono::system_clock::now().time_since_epoch());
    const std::int64_t after = ns(std::chrono::steady_clock::now().time_since_epoch());
    if (best.bracket_ns < 0 || after - before < best.bracket_ns)
      best = {before + (after - before) / 2, wall, after - before};
    if (best.bracket_ns < 20'000) break;  // a few µs is the clocks' own cost: nothing was in between
  }
  return best;
}

}  // namespace zenith::core
