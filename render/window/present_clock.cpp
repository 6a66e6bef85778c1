#include "render/window/present_clock.h"

#include <algorithm>

namespace zenith::render::window {

PresentClock::PresentClock(double refresh_hz, double margin) : refresh_hz_(refresh_hz), margin_(margin) {}

bool PresentClock::record(Clock::time_point asked, Clock::time_point done) {
  ++presented_;
  const double ms = std::chrono::duration<double, std::milli>(done - asked).count();
  worst_ms_ = std::max(worst_ms_, ms);
  if (refresh_hz_ <= 0.0) return false;
  const bool late = ms > (1.0 + margin_) * 1000.0 / refresh_hz_;
  if (late) ++late_;
  return late;
}

}  // namespace zenith::render::window
