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

/// `text` safe to write into a log line: printable ASCII and printable UTF-8
/// characters ("°", "é") as they are, a backslash doubled, every other byte
/// as \xNN — control characters (a newline, escape codes, C1 controls),
/// bytes that are not well-formed UTF-8, and the characters that move or hide
/// text (line separators, bidirectional overrides, zero-width ones); longer
/// than `max_bytes`, cut there with "…(N bytes)". Every string a peer sends
/// (an OSC address, a Host header, a node name) goes through it before it is
/// logged, so no peer can forge or colour a log line.
std::string escaped(std::string_view text, std::size_t max_bytes = 200);

}  // namespace zenith::core
