#pragma once
// Whether a presented frame reached the display at the refresh it was meant
// for: the hook the cluster's late-frame counts build on (issue 26, pacing).
// A node swaps right after the Present it receives; with vsync the swap (and
// a glFinish after it) completes at the next vertical blank. If more than one
// refresh period (plus a margin for the clock's jitter) passes between the
// Present and the completed swap, the frame missed the vblank that followed
// the Present: it was shown a refresh late.
#include <chrono>
#include <cstdint>

namespace zenith::render::window {

class PresentClock {
 public:
  using Clock = std::chrono::steady_clock;
  /// `refresh_hz` ≤ 0 (unknown, or vsync off): no frame is ever counted late.
  explicit PresentClock(double refresh_hz = 0.0, double margin = 0.25);

  /// A Present received at `asked` whose swap completed at `done`; returns
  /// whether it was late: done − asked > (1 + margin) · the refresh period.
  bool record(Clock::time_point asked, Clock::time_point done);

  std::uint64_t presented() const { return presented_; }
  std::uint64_t late() const { return late_; }
  /// The longest Present-to-swap time so far, in milliseconds.
  double worst_ms() const { return worst_ms_; }
  double refresh_hz() const { return refresh_hz_; }

 private:
  double refresh_hz_ = 0.0, margin_ = 0.25;
  std::uint64_t presented_ = 0, late_ = 0;
  double worst_ms_ = 0.0;
};

}  // namespace zenith::render::window
