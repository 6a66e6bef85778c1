#pragma once
// Rate limits for log lines a peer can cause (refused connections, bad OSC
// packets, failed accepts): the first of a kind in a window is logged, the
// rest are counted and summed up in the next line ("… and 39999 more in the
// last 1 s"), so a flood costs one line a second instead of one per packet.
// Pure logic: the caller passes the clock and writes the line.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace zenith::core {

/// Invariant: at most one line per `window`; no event is lost from the count.
class LogLimiter {
 public:
  using Clock = std::chrono::steady_clock;

  explicit LogLimiter(std::chrono::milliseconds window = std::chrono::milliseconds(1000)) : window_(window) {}

  /// One event at `now`. Returns the suffix to log it with — "" for the first
  /// in a window, " (and 39999 more in the last 1 s)" when earlier ones were
  /// held back — or nullopt when it is only counted.
  std::optional<std::string> admit(Clock::time_point now);
  /// Events counted but not yet reported.
  std::uint64_t suppressed() const { return suppressed_; }
  /// Events seen in all.
  std::uint64_t total() const { return total_; }

 private:
  std::chrono::milliseconds window_;
  std::optional<Clock::time_point> last_logged_;
  std::uint64_t suppressed_ = 0;
  std::uint64_t total_ = 0;
};

}  // namespace zenith::core
