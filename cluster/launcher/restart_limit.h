#pragma once
// When `zenith cluster --restart-nodes` restarts a node process that died
// (docs/cluster.md, "Join, rejoin and failures"): every death but a clean
// exit, at most `max_restarts` times within any `window`, so a crash loop
// does not spin. No processes and no clock: the launcher
// (apps/cluster_commands.cpp) asks it with the time of each death.
#include <chrono>
#include <cstdint>
#include <deque>

namespace zenith::app {

/// Invariants: allow() counts the restarts it grants; it grants one when fewer
/// than max_restarts were granted in the window before `now`. Once it refuses,
/// it refuses for good (gave_up()): the launcher leaves the node down rather
/// than wait out a crash loop.
class RestartLimit {
 public:
  using Clock = std::chrono::steady_clock;

  /// `max_restarts` ≥ 1, `window` > 0.
  RestartLimit(std::uint32_t max_restarts, std::chrono::milliseconds window);

  /// Whether a process that ended with `exit_status` (128 + signal when a
  /// signal killed it) died: anything but 0 (0: the master's Goodbye, or a
  /// SIGTERM it obeyed).
  static bool died(int exit_status) { return exit_status != 0; }

  /// The process died at `now`: true, and the restart counted, when it may be
  /// restarted; false (for good) when max_restarts were made in the window.
  bool allow(Clock::time_point now);

  bool gave_up() const { return gave_up_; }
  /// Restarts granted in the window before `now`.
  std::uint32_t recent(Clock::time_point now) const;
  std::uint32_t total() const { return total_; }
  std::uint32_t max_restarts() const { return max_restarts_; }
  std::chrono::milliseconds window() const { return window_; }

 private:
  std::uint32_t max_restarts_;
  std::chrono::milliseconds window_;
  std::deque<Clock::time_point> granted_;  ///< within the window, oldest first
  std::uint32_t total_ = 0;
  bool gave_up_ = false;
};

}  // namespace zenith::app
