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
//
// Frame 0 is the warm-up frame: the nodes build their programs for the
// show's first state, allocate their buffers, upload the tables and swap
// their windows for the first time while rendering it, which can take many
// periods. The master starts the schedule (start()) at frame 0's Present, so
// frame 1 is due one period after it; frame 0 is never late, and the late
// count starts at frame 1, the first paced frame (cluster/master/frame_loop.cpp).
#include <chrono>
#include <cstdint>

namespace zenith::cluster {

class FramePacer {
 public:
  using Clock = std::chrono::steady_clock;

  /// `rate_hz` > 0 (the config's frame_rate_hz).
  explicit FramePacer(double rate_hz);

  /// Frame 0 is due (the warm-up frame was presented) at `t0`: frame n ≥ 1 at t0 + n / rate.
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

  /// Whether frame `n`, presented at `presented`, was late: more than one
  /// period after it was due. Never frame 0, the warm-up frame.
  bool late(std::uint64_t n, Clock::time_point presented) const { return n > 0 && presented - due(n) > period_; }

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
