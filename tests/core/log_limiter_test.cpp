// core::LogLimiter (core/log_limiter.h): a flood of refusals is one log line
// a window with the count held back (an OSC flood once logged a line per
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

// A flood of one kind (bad magic bytes) once hid the first line of another
// (an oversized header) that came within the same second.
TEST(LogLimiters, EachKindHasItsOwnWindowAndTheKindsAreBounded) {
  LogLimiters limiters(1000ms);
  const LogLimiter::Clock::time_point t0{};
  const std::string magic = LogLimiters::kind_of("protocol error: bad_magic: frame header magic: 0x0781ee11");
  const std::string oversized =
      LogLimiters::kind_of("protocol error: oversized: frame header payload length: 1048616 bytes of a TableChunk");
  EXPECT_EQ(magic, "protocol error: bad_magic");
  EXPECT_EQ(oversized, "protocol error: oversized");
  EXPECT_EQ(LogLimiters::kind_of("end of stream inside a frame (10 bytes of a truncated frame)"),
            LogLimiters::kind_of("end of stream inside a frame (7 bytes of a truncated frame)"))
      << "the numbers do not make a new kind";
  EXPECT_TRUE(limiters.admit(magic, t0).has_value());
  for (int i = 1; i < 100; ++i) EXPECT_FALSE(limiters.admit(magic, t0 + std::chrono::milliseconds(i)).has_value());
  EXPECT_EQ(limiters.admit(oversized, t0 + 200ms), std::optional<std::string>("")) << "another kind: its first line";
  EXPECT_EQ(limiters.admit(magic, t0 + 1100ms), std::optional<std::string>(" (and 99 more in the last 1.1 s)"));
  // Kinds past the bound share one limiter: a peer cannot grow the map.
  int logged = 0;
  for (std::size_t k = 0; k < 10 * LogLimiters::kMaxKinds; ++k)
    logged += limiters.admit("kind " + std::string(k + 1, 'x'), t0 + 2000ms).has_value() ? 1 : 0;
  EXPECT_EQ(logged, static_cast<int>(LogLimiters::kMaxKinds) - 2 + 1) << "30 new kinds, then one line for all the rest";
}

}  // namespace
}  // namespace zenith::core
