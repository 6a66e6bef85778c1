#include "cluster/launcher/restart_limit.h"

#include <algorithm>
#include <stdexcept>

namespace zenith::app {

RestartLimit::RestartLimit(std::uint32_t max_restarts, std::chrono::milliseconds window)
    : max_restarts_(max_restarts), window_(window) {
  if (max_restarts_ < 1) throw std::invalid_argument("RestartLimit: at least one restart");
  if (window_.count() <= 0) throw std::invalid_argument("RestartLimit: the window must be positive");
}

bool RestartLimit::allow(Clock::time_point now) {
  if (gave_up_) return false;
  while (!granted_.empty() && now - granted_.front() >= window_) granted_.pop_front();
  if (granted_.size() >= max_restarts_) {
    gave_up_ = true;
    return false;
  }
  granted_.push_back(now);
  ++total_;
  return true;
}

std::uint32_t RestartLimit::recent(Clock::time_point now) const {
  return static_cast<std::uint32_t>(
      std::count_if(granted_.begin(), granted_.end(), [&](const Clock::time_point t) { return now - t < window_; }));
}

}  // namespace zenith::app
