#include "core/strings.h"

#include <algorithm>
#include <cstdint>

namespace zenith::core {

namespace {

/// The code point of the well-formed UTF-8 sequence at `text[i]` and its
/// length, or length 0 when the bytes there are not one (a stray
/// continuation byte, a truncated sequence, an overlong form, a surrogate, a
/// code point above U+10FFFF).
struct Decoded {
  std::uint32_t code_point = 0;
  std::size_t length = 0;
};
Decoded decode_utf8(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  std::uint32_t cp = 0;
  if (lead >= 0xc2 && lead <= 0xdf)
    length = 2, cp = lead & 0x1fu;
  else if (lead >= 0xe0 && lead <= 0xef)
    length = 3, cp = lead & 0x0fu;
  else if (lead >= 0xf0 && lead <= 0xf4)
    length = 4, cp = lead & 0x07u;
  else
    return {};
  if (i + length > text.size()) return {};
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return {};
    cp = (cp << 6) | (byte(i + k) & 0x3fu);
  }
  const std::uint32_t smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < smallest[length] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return {};
  return {cp, length};
}

/// Code points that are not shown as themselves: C1 controls, and those that
/// move or hide text on a terminal or in a viewer (line and paragraph
/// separators, bidirectional overrides and isolates, zero-width characters,
/// the byte-order mark), so a peer cannot make a line read otherwise.
bool is_invisible_or_control(std::uint32_t cp) {
  return (cp >= 0x80 && cp <= 0x9f) || (cp >= 0x200b && cp <= 0x200f) || (cp >= 0x2028 && cp <= 0x202e) ||
         (cp >= 0x2060 && cp <= 0x2069) || cp == 0xfeff;
}

}  // namespace

std::string escaped(std::string_view text, std::size_t max_bytes) {
  constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  const std::size_t shown = std::min(text.size(), max_bytes);
  out.reserve(shown + 16);
  const auto hex = [&](unsigned char c) {
    out += "\\x";
    out += kHex[c >> 4];
    out += kHex[c & 0xf];
  };
  for (std::size_t i = 0; i < shown;) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\\') {
      out += "\\\\";
      ++i;
    } else if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
      ++i;
    } else if (const Decoded d = c >= 0x80 ? decode_utf8(text.substr(0, shown), i) : Decoded{};
               d.length > 0 && !is_invisible_or_control(d.code_point)) {
      out.append(text.substr(i, d.length));  // a printable character ("°", "é"): as is
      i += d.length;
    } else {
      hex(c);
      ++i;
    }
  }
  if (shown < text.size()) out += cat("…(", text.size(), " bytes)");
  return out;
}

}  // namespace zenith::core
