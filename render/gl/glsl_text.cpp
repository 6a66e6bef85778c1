#include "render/gl/glsl_text.h"

#include <fmt/format.h>

#include <cctype>
#include <map>
#include <utility>

namespace zenith::render::gl::glsl_text {

std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    const std::size_t newline = text.find('\n');
    lines.push_back(text.substr(0, newline));
    if (newline == std::string_view::npos) break;
    text.remove_prefix(newline + 1);
  }
  return lines;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> directive_words(std::string_view line) {
  line = trim(line);
  std::vector<std::string_view> words;
  if (line.empty() || line.front() != '#') return words;
  line.remove_prefix(1);
  while (true) {
    line = trim(line);
    if (line.empty()) break;
    std::size_t end = 0;
    while (end < line.size() && !std::isspace(static_cast<unsigned char>(line[end]))) ++end;
    words.push_back(line.substr(0, end));
    line.remove_prefix(end);
  }
  return words;
}

std::optional<int> parse_int(std::string_view s) {
  if (s.empty() || s.size() > 9) return std::nullopt;
  int v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
    v = v * 10 + (c - '0');
  }
  return v;
}

namespace {

/// (source-string number, line) → that line's text, following the #line
/// directives of the compiled text.
std::map<std::pair<int, int>, std::string_view> line_map(std::string_view text) {
  std::map<std::pair<int, int>, std::string_view> map;
  int string = 0, line = 1;
  for (std::string_view l : split_lines(text)) {
    const std::vector<std::string_view> words = directive_words(l);
    if (words.size() >= 2 && words[0] == "line") {
      if (auto n = parse_int(words[1])) {
        line = *n;
        if (words.size() >= 3)
          if (auto s = parse_int(words[2])) string = *s;
        continue;
      }
    }
    map.insert_or_assign({string, line}, l);  // later (original) lines win over injected ones
    ++line;
  }
  return map;
}

/// The (source string, line) a compiler message names: "0:7(12): ..." (Mesa),
/// "0(7) : ..." (NVIDIA), "ERROR: 0:7: ..." (others).
std::optional<std::pair<int, int>> message_location(std::string_view message) {
  for (std::string_view prefix : {"ERROR: ", "WARNING: "})
    if (message.substr(0, prefix.size()) == prefix) message.remove_prefix(prefix.size());
  std::size_t i = 0;
  auto digits = [&]() -> std::optional<int> {
    const std::size_t start = i;
    while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
    return parse_int(message.substr(start, i - start));
  };
  const auto string = digits();
  if (!string || i >= message.size()) return std::nullopt;
  const char separator = message[i++];
  if (separator != ':' && separator != '(') return std::nullopt;
  const auto line = digits();
  if (!line || i >= message.size()) return std::nullopt;
  if (separator == '(' && message[i] != ')') return std::nullopt;
  if (separator == ':' && message[i] != '(' && message[i] != ':') return std::nullopt;
  return std::pair{*string, *line};
}

}  // namespace

std::string annotate_log(std::string_view log, std::string_view compiled, const std::vector<std::string>& files) {
  const auto map = line_map(compiled);
  std::string out;
  for (std::string_view message : split_lines(log)) {
    while (!message.empty() && message.back() == '\r') message.remove_suffix(1);
    if (trim(message).empty()) continue;
    out += fmt::format("{}\n", message);
    if (auto where = message_location(message)) {
      const auto [string, line] = *where;
      const std::string file = string >= 0 && static_cast<std::size_t>(string) < files.size()
                                   ? files[static_cast<std::size_t>(string)]
                                   : fmt::format("source {}", string);
      if (auto it = map.find({string, line}); it != map.end())
        out += fmt::format("    {}:{} | {}\n", file, line, trim(it->second));
    }
  }
  if (files.size() > 1) {
    out += "source strings:";
    for (std::size_t k = 0; k < files.size(); ++k)
      out += fmt::format(" {} = {}{}", k, files[k], k + 1 < files.size() ? "," : "");
    out += '\n';
  }
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

}  // namespace zenith::render::gl::glsl_text
