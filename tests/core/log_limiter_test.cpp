// core::LogLimiter (core/log_limiter.h): a flood of refusals is one log line
// a window with the count held back (issue 30: an OSC flood logged a line per
// packet; EMFILE wrote a million lines in 4 s).
#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <string>

#include "core/log_limiter.h"

namespace zenith::core {
namespace {

using namespace std::chrono_literals;

TEST(LogLimiter, OneLineAWindowAndTheNextSaysHowManyWereHeldBack) {
  LogLimiter limiter(1000ms);
  const LogLimiter::Clock::time_point t0{};
  EXPECT_EQ(limiter.admit(t0), std::optional<std::string>("")) << "the first is logged as is";
  int logged = 0;
  for (int i = 1; i <= 39999; ++i)  // 39 999 more within the window: counted, not logged
    logged += limiter.admit(t0 + std::chrono::microseconds(i * 20)).has_value() ? 1 : 0;
  EXPECT_EQ(logged, 0);
  EXPECT_EQ(limiter.suppressed(), 39999u);
  EXPECT_EQ(limiter.admit(t0 + 1500ms), std::optional<std::string>(" (and 39999 more in the last 1.5 s)"));
  EXPECT_EQ(limiter.suppressed(), 0u);
  EXPECT_EQ(limiter.total(), 40001u) << "no event lost from the count";
  EXPECT_FALSE(limiter.admit(t0 + 1999ms).has_value()) << "the window starts at the last line logged";
  EXPECT_EQ(limiter.admit(t0 + 2500ms), std::optional<std::string>(" (and 1 more in the last 1.0 s)"));
  EXPECT_EQ(limiter.admit(t0 + 10s), std::optional<std::string>("")) << "a quiet window: nothing to add";
}

}  // namespace
}  // namespace zenith::core
