// The wall clock paired with the steady clock at one moment (core/wall_clock.h).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <thread>

#include "core/wall_clock.h"

namespace zenith::core {
namespace {

std::int64_t steady_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Two pairings 50 ms apart see the same wall − steady difference, within their
// brackets (and the few µs NTP may slew the wall clock by in 50 ms); each
// steady time lies between readings taken around the call.
TEST(WallClock, TwoPairingsAgreeWithinTheirBrackets) {
  const std::int64_t before = steady_now_ns();
  const WallAtSteady a = wall_at_steady();
  const std::int64_t after = steady_now_ns();
  EXPECT_GE(a.steady_ns, before);
  EXPECT_LE(a.steady_ns, after);
  EXPECT_GE(a.bracket_ns, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const WallAtSteady b = wall_at_steady();
  const std::int64_t drift_ns = (b.wall_ns - b.steady_ns) - (a.wall_ns - a.steady_ns);
  EXPECT_LE(std::llabs(drift_ns), a.bracket_ns / 2 + b.bracket_ns / 2 + 50'000)
      << "brackets " << a.bracket_ns << " and " << b.bracket_ns << " ns";
  EXPECT_GT(b.steady_ns - a.steady_ns, 50'000'000);
}

}  // namespace
}  // namespace zenith::core
