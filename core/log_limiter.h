#pragma once
// Rate limits for log lines a peer can cause (refused connections, bad OSC
// packets, failed accepts): the first of a kind in a window is logged, the
// rest are counted and summed up in the next line ("… and 39999 more in the
// last 1 s"), so a flood costs one line a second instead of one per packet.
// Pure logic: the caller passes the clock and writes the line.
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>

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

/// One LogLimiter per kind of event, so that a flood of one kind (bad magic
/// bytes) never hides the first line of another (an oversized header, a
/// wrong secret). The kind is the caller's (a reason without its numbers:
/// kind_of()); past kMaxKinds distinct kinds the rest share one limiter, so
/// the map stays small whatever the peers send.
class LogLimiters {
 public:
  static constexpr std::size_t kMaxKinds = 32;
  explicit LogLimiters(std::chrono::milliseconds window = std::chrono::milliseconds(1000))
      : window_(window), others_(window) {}
  /// LogLimiter::admit for the limiter of `kind`.
  std::optional<std::string> admit(std::string_view kind, LogLimiter::Clock::time_point now);

  /// The kind of a reason text for admit(): its first two ':'-separated
  /// fields without digits ("protocol error: oversized: frame header payload
  /// length: 1048616 bytes…" → "protocol error: oversized"; "end of stream
  /// inside a frame (10 bytes…)" → "end of stream inside a frame ( bytes…)").
  static std::string kind_of(std::string_view reason);

 private:
  std::chrono::milliseconds window_;
  std::map<std::string, LogLimiter, std::less<>> kinds_;
  LogLimiter others_;
};

}  // namespace zenith::core
