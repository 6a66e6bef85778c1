#include "warp/xml_reader.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace zenith::warp {
namespace {

constexpr int kMaxDepth = 256;  // deeper nesting is no configuration file

char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

bool is_name_start(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_' || c == ':' ||
         static_cast<unsigned char>(c) >= 0x80;
}
bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9') || c == '-' || c == '.'; }

void append_utf8(std::string& out, std::uint32_t code) {
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

class Parser {
 public:
  Parser(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  XmlElement document() {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") advance(3);
    bool seen_markup = false;  // a comment or processing instruction before a declaration is an error
    // Prolog: declaration, comments, processing instructions, whitespace.
    for (;;) {
      skip_space();
      if (at_end()) fail("no root element");
      if (starts_with("<?")) {
        const bool declaration = starts_with_ignoring_case("<?xml") && pos_ + 5 < text_.size() &&
                                 (is_space(text_[pos_ + 5]) || text_[pos_ + 5] == '?');
        if (declaration && seen_markup) fail("the XML declaration must come first");
        seen_markup = true;
        skip_past("?>", "processing instruction");
      } else if (starts_with("<!--")) {
        seen_markup = true;
        skip_comment();
      } else if (starts_with("<!")) {
        fail("DTDs and <! declarations are not supported");
      } else if (starts_with("<")) {
        break;
      } else {
        fail("text before the root element");
      }
    }
    XmlElement root = element(0);
    // Epilogue: comments, processing instructions, whitespace.
    for (;;) {
      skip_space();
      if (at_end()) break;
      if (starts_with("<!--")) {
        skip_comment();
      } else if (starts_with("<?")) {
        skip_past("?>", "processing instruction");
      } else if (starts_with("<")) {
        fail("a second root element");
      } else {
        fail("text after the root element");
      }
    }
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { fail_at(line_, what); }
  [[noreturn]] void fail_at(int line, const std::string& what) const {
    throw std::runtime_error(source_ + ":" + std::to_string(line) + ": malformed XML: " + what);
  }

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  bool starts_with(std::string_view prefix) const { return text_.substr(pos_, prefix.size()) == prefix; }
  bool starts_with_ignoring_case(std::string_view prefix) const {
    return equals_ignoring_case(text_.substr(pos_, prefix.size()), prefix);
  }
  void advance(std::size_t count) {
    for (std::size_t k = 0; k < count && pos_ < text_.size(); ++k)
      if (text_[pos_++] == '\n') ++line_;
  }
  void skip_space() {
    while (!at_end() && is_space(peek())) advance(1);
  }
  void expect(char c, const char* context) {
    if (peek() != c) {
      if (at_end()) fail(std::string("unexpected end of input in ") + context);
      fail(std::string("expected '") + c + "' in " + context + ", found '" + peek() + "'");
    }
    advance(1);
  }
  /// Skips up to and including `terminator`.
  void skip_past(std::string_view terminator, const char* what) {
    const int start_line = line_;
    const std::size_t end = text_.find(terminator, pos_);
    if (end == std::string_view::npos) fail_at(start_line, std::string("unterminated ") + what);
    advance(end + terminator.size() - pos_);
  }
  void skip_comment() {
    const int start_line = line_;
    advance(4);
    const std::size_t end = text_.find("--", pos_);
    if (end == std::string_view::npos) fail_at(start_line, "unterminated comment");
    advance(end - pos_);
    if (!starts_with("-->")) fail("'--' inside a comment");
    advance(3);
  }

  std::string name(const char* what) {
    if (!is_name_start(peek())) {
      if (at_end()) fail(std::string("unexpected end of input, expected ") + what);
      fail(std::string("expected ") + what + ", found '" + peek() + "'");
    }
    const std::size_t start = pos_;
    while (!at_end() && is_name_char(peek())) advance(1);
    return std::string(text_.substr(start, pos_ - start));
  }

  /// Decodes the entity at pos_ ('&') into `out`.
  void entity(std::string& out) {
    const std::size_t end = text_.find(';', pos_);
    if (end == std::string_view::npos || end - pos_ > 12) fail("'&' not followed by an entity reference ending in ';'");
    const std::string_view ref = text_.substr(pos_ + 1, end - pos_ - 1);
    if (ref == "lt") {
      out += '<';
    } else if (ref == "gt") {
      out += '>';
    } else if (ref == "amp") {
      out += '&';
    } else if (ref == "quot") {
      out += '"';
    } else if (ref == "apos") {
      out += '\'';
    } else if (ref.size() >= 2 && ref[0] == '#') {
      const bool hex = ref[1] == 'x';
      const std::string_view digits = ref.substr(hex ? 2 : 1);
      std::uint32_t code = 0;
      const auto [ptr, error] = std::from_chars(digits.data(), digits.data() + digits.size(), code, hex ? 16 : 10);
      if (digits.empty() || error != std::errc() || ptr != digits.data() + digits.size() || code == 0 ||
          code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF))
        fail("bad character reference '&" + std::string(ref) + ";'");
      append_utf8(out, code);
    } else {
      fail("unknown entity '&" + std::string(ref) + ";' (DTD entities are not supported)");
    }
    advance(end + 1 - pos_);
  }

  std::string attribute_value() {
    const char quote = peek();
    if (quote != '"' && quote != '\'') fail("attribute value must be quoted");
    const int start_line = line_;
    advance(1);
    std::string value;
    for (;;) {
      if (at_end()) fail_at(start_line, "unterminated attribute value");
      const char c = peek();
      if (c == quote) break;
      if (c == '<') fail("'<' in an attribute value");
      if (c == '&') {
        entity(value);
      } else {
        value += c;
        advance(1);
      }
    }
    advance(1);
    return value;
  }

  XmlElement element(int depth) {
    if (depth > kMaxDepth) fail("elements nested deeper than " + std::to_string(kMaxDepth));
    XmlElement result;
    result.line = line_;
    expect('<', "a start tag");
    result.name = name("an element name");
    for (;;) {
      const bool had_space = !at_end() && is_space(peek());
      skip_space();
      if (starts_with("/>")) {
        advance(2);
        return result;
      }
      if (peek() == '>') {
        advance(1);
        break;
      }
      if (at_end()) fail_at(result.line, "unexpected end of input in the start tag of <" + result.name + ">");
      if (!had_space) fail("expected whitespace, '>' or '/>' in the start tag of <" + result.name + ">");
      std::string attribute_name = name("an attribute name");
      for (const auto& [existing, unused] : result.attributes)
        if (equals_ignoring_case(existing, attribute_name))
          fail("duplicate attribute '" + attribute_name + "' on <" + result.name + ">");
      skip_space();
      expect('=', "an attribute");
      skip_space();
      result.attributes.emplace_back(std::move(attribute_name), attribute_value());
    }
    // Content.
    for (;;) {
      if (at_end()) fail_at(result.line, "<" + result.name + "> is never closed");
      if (starts_with("</")) {
        const int close_line = line_;
        advance(2);
        const std::string closing = name("an element name");
        skip_space();
        expect('>', "an end tag");
        if (!equals_ignoring_case(closing, result.name))
          fail_at(close_line,
                  "</" + closing + "> closes <" + result.name + "> opened at line " + std::to_string(result.line));
        return result;
      }
      if (starts_with("<!--")) {
        skip_comment();
      } else if (starts_with("<![CDATA[")) {
        const int start_line = line_;
        advance(9);
        const std::size_t end = text_.find("]]>", pos_);
        if (end == std::string_view::npos) fail_at(start_line, "unterminated CDATA section");
        result.text += text_.substr(pos_, end - pos_);
        advance(end + 3 - pos_);
      } else if (starts_with("<!")) {
        fail("DTDs and <! declarations are not supported");
      } else if (starts_with("<?")) {
        skip_past("?>", "processing instruction");
      } else if (peek() == '<') {
        result.children.push_back(element(depth + 1));
      } else if (peek() == '&') {
        entity(result.text);
      } else {
        result.text += peek();
        advance(1);
      }
    }
  }

  std::string_view text_;
  const std::string& source_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

}  // namespace

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (lower(a[k]) != lower(b[k])) return false;
  return true;
}

const std::string* XmlElement::attribute(std::string_view attribute_name) const {
  for (const auto& [key, value] : attributes)
    if (equals_ignoring_case(key, attribute_name)) return &value;
  return nullptr;
}

const XmlElement* XmlElement::child(std::string_view element_name) const {
  for (const XmlElement& element : children)
    if (element.is(element_name)) return &element;
  return nullptr;
}

std::vector<const XmlElement*> XmlElement::children_named(std::string_view element_name) const {
  std::vector<const XmlElement*> found;
  for (const XmlElement& element : children)
    if (element.is(element_name)) found.push_back(&element);
  return found;
}

XmlElement parse_xml(std::string_view document, const std::string& source) {
  return Parser(document, source).document();
}

std::string_view trimmed(std::string_view text) {
  const auto space = [](unsigned char c) { return std::isspace(c) != 0; };
  while (!text.empty() && space(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && space(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  return text;
}

std::optional<double> finite_number(std::string_view text) {
  std::string_view digits = trimmed(text);
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

}  // namespace zenith::warp
