#include "core/log_limiter.h"

#include <cstdio>

#include "core/strings.h"

namespace zenith::core {

std::optional<std::string> LogLimiter::admit(Clock::time_point now) {
  ++total_;
  if (last_logged_ && now - *last_logged_ < window_) {
    ++suppressed_;
    return std::nullopt;
  }
  std::string suffix;
  if (suppressed_ > 0) {
    const double seconds = std::chrono::duration<double>(now - *last_logged_).count();
    char elapsed[32];
    std::snprintf(elapsed, sizeof elapsed, "%.1f", seconds);
    suffix = cat(" (and ", suppressed_, " more in the last ", elapsed, " s)");
  }
  suppressed_ = 0;
  last_logged_ = now;
  return suffix;
}

}  // namespace zenith::core
