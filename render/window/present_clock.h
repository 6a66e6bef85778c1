#pragma once
// Whether a presented frame reached the display at the refresh it was meant
// for: the hook the cluster's late-frame counts build on.
// A node swaps right after the Present it receives; with vsync the swap (and
// a glFinish after it) completes at the next vertical blank. If more than one
// refresh period (plus a margin for the clock's jitter) passes between the
// Present and the completed swap, the frame missed the vblank that followed
// the Present: it was shown a refresh late.
//
// Where the display's vblank counter is known (GLX_OML_sync_control,
// render/window/swap_sync.h), the count is exact instead: a present whose
// swap completed more than one vblank after the present began was late,
// whatever the wall clock's jitter.
#include <chrono>
#include <cstdint>
#include <optional>

namespace zenith::render::window {

class PresentClock {
 public:
  using Clock = std::chrono::steady_clock;
  /// `refresh_hz` ≤ 0 (unknown, or vsync off): no frame is ever counted late.
  explicit PresentClock(double refresh_hz = 0.0, double margin = 0.25);

  /// A Present received at `asked` whose swap completed at `done`; returns
  /// whether it was late: done − asked > (1 + margin) · the refresh period,
  /// or, with `vblanks` (the display's vblank counter advanced by that much
  /// from the start of the present to the completed swap), vblanks > 1.
  bool record(Clock::time_point asked, Clock::time_point done, std::optional<std::int64_t> vblanks = std::nullopt);

  std::uint64_t presented() const { return presented_; }
  std::uint64_t late() const { return late_; }
  /// The longest Present-to-swap time so far, in milliseconds.
  double worst_ms() const { return worst_ms_; }
  /// The latest Present-to-swap time, in milliseconds (0 before the first).
  double last_ms() const { return last_ms_; }
  double refresh_hz() const { return refresh_hz_; }

 private:
  double refresh_hz_ = 0.0, margin_ = 0.25;
  std::uint64_t presented_ = 0, late_ = 0;
  double worst_ms_ = 0.0, last_ms_ = 0.0;
};

}  // namespace zenith::render::window
