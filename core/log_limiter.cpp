#include "core/log_limiter.h"

#include <algorithm>
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

std::optional<std::string> LogLimiters::admit(std::string_view kind, LogLimiter::Clock::time_point now) {
  auto it = kinds_.find(kind);
  if (it == kinds_.end()) {
    if (kinds_.size() >= kMaxKinds) return others_.admit(now);
    it = kinds_.emplace(std::string(kind), LogLimiter(window_)).first;
  }
  return it->second.admit(now);
}

std::string LogLimiters::kind_of(std::string_view reason) {
  const std::size_t first = reason.find(':');
  const std::size_t second = first == std::string_view::npos ? first : reason.find(':', first + 1);
  std::string kind;
  for (const char c : reason.substr(0, std::min<std::size_t>(second, 80)))
    if (c < '0' || c > '9') kind += c;
  return kind;
}

}  // namespace zenith::core
