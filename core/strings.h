#pragma once
// Strings for messages: every module's error messages and log lines are
// joined with cat (no JSON, no formatting library needed to include it).
#include <cstddef>
#include <sstream>
#include <string>
#include <string_view>

namespace zenith::core {

/// Concatenation through a stream: cat("frame ", 42, ": ", what). (GCC 12
/// warns falsely on chains of std::string +.)
template <typename... T>
std::string cat(const T&... parts) {
  std::ostringstream s;
  (s << ... << parts);
  return s.str();
}

/// How often `needle` occurs in `text`, overlaps included (log lines a test or a benchmark counts).
inline std::size_t count_of(std::string_view text, std::string_view needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string_view::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

}  // namespace zenith::core
