#pragma once
// When the master starts each frame (docs/cluster.md, "Pacing"): frame N is
// due at t0 + N / rate, the rate being the cluster's `frame_rate_hz` (up to
// kMaxFrameRateHz, the display's rate on a live dome: 60 or 120 Hz). Nodes
// swap right after the Present they receive, so the master's schedule is the
// projectors' schedule; vsync (or a swap group) then puts each swap on a
// vertical blank.
//
// A frame that cannot start when due (a node rendering slowly, a table set
// not ready) starts as soon as it can; if the cluster fell more than one
// period behind, the schedule moves to "now" instead of bursting frames to
// catch up (a burst would show several frames in a few vblanks, which looks
// worse on a dome than one held frame). Each such slip is counted. Time is
// passed in, so the rule is tested without sockets (tests/cluster/frame_pacer_test.cpp).
#include <chrono>
#include <cstdint>

namespace zenith::cluster {

class FramePacer {
 public:
  using Clock = std::chrono::steady_clock;

  /// `rate_hz` > 0 (the config's frame_rate_hz).
  explicit FramePacer(double rate_hz);

  /// Frame 0 starts at `t0`.
  void start(Clock::time_point t0);
  /// The show waited `waited` (for a table set): the later frames keep the
  /// rate from the end of the wait instead of catching up on it.
  void hold(Clock::duration waited) { t0_ += waited; }
  /// When frame `n` (counted from the start) is due.
  Clock::time_point due(std::uint64_t n) const;
  /// How long to wait at `now` before frame `n` may start: 0 when it is due.
  /// More than one period late, the schedule moves so that frame `n` is due
  /// now (counted in slips()).
  Clock::duration wait_before(std::uint64_t n, Clock::time_point now);

  double rate_hz() const { return rate_hz_; }
  Clock::duration period() const { return period_; }
  /// Times the schedule moved because the cluster fell more than a period behind.
  std::uint64_t slips() const { return slips_; }

 private:
  double rate_hz_;
  Clock::duration period_;
  Clock::time_point t0_{};
  std::uint64_t slips_ = 0;
};

}  // namespace zenith::cluster
