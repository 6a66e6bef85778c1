#pragma once
// A small, strict XML reader for configuration files such as MPCDI's mpcdi.xml.
//
// Reads: an optional UTF-8 byte-order mark, the XML declaration, comments,
// processing instructions (skipped), one root element with attributes (single
// or double quotes), nested elements, character data, CDATA sections and the
// entities &lt; &gt; &amp; &quot; &apos; &#N; &#xN;. Rejects, with the line: a
// DTD (<!DOCTYPE>), unknown entities, unclosed or mismatched tags, duplicate
// attributes, '<' in an attribute value, text or a second element after the
// root, and an unexpected end of input.
//
// Names are kept as written; lookups (XmlElement::child, attribute, is) compare
// them ASCII case-insensitively, as MPCDI requires. Namespaces are not
// interpreted (a prefix is part of the name).
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace zenith::warp {

/// ASCII case-insensitive equality.
bool equals_ignoring_case(std::string_view a, std::string_view b);
/// `text` without leading and trailing whitespace.
std::string_view trimmed(std::string_view text);
/// The finite number `text` holds (surrounding whitespace and a leading '+'
/// allowed; std::from_chars's format otherwise); nothing for anything else.
/// The numbers of MPCDI descriptors and of the files they name (.cube LUTs).
std::optional<double> finite_number(std::string_view text);

struct XmlElement {
  std::string name;
  int line = 0;                                                 ///< line of the start tag's '<', 1-based
  std::vector<std::pair<std::string, std::string>> attributes;  ///< in document order, values decoded
  std::string text;  ///< the character data directly inside, concatenated, decoded
  std::vector<XmlElement> children;

  /// Whether the element's name is `element_name` (ignoring case).
  bool is(std::string_view element_name) const { return equals_ignoring_case(name, element_name); }
  /// The value of an attribute (name ignoring case); nullptr when absent.
  const std::string* attribute(std::string_view attribute_name) const;
  /// The first child element with that name (ignoring case); nullptr when absent.
  const XmlElement* child(std::string_view element_name) const;
  /// Every child element with that name (ignoring case), in document order.
  std::vector<const XmlElement*> children_named(std::string_view element_name) const;
};

/// Parses a document and returns its root element. Throws std::runtime_error
/// "<source>:<line>: <what is wrong>".
XmlElement parse_xml(std::string_view document, const std::string& source);

}  // namespace zenith::warp
