// core::escaped (core/strings.h): what every peer-supplied string becomes
// before it is logged (an OSC address with a newline once forged a
// log line, escape codes coloured the terminal).
#include <gtest/gtest.h>

#include <string>

#include "core/strings.h"

namespace zenith::core {
namespace {

TEST(Escaped, PrintableAsciiPassesControlBytesBecomeHexAndABackslashIsDoubled) {
  EXPECT_EQ(escaped("/zenith/exposure 1.5"), "/zenith/exposure 1.5");
  EXPECT_EQ(escaped("a\nmaster: quit"), "a\\x0amaster: quit") << "no second log line";
  EXPECT_EQ(escaped("\x1b[2J"), "\\x1b[2J") << "no terminal escape";
  EXPECT_EQ(escaped(std::string("nul\0x", 5)), "nul\\x00x");
  EXPECT_EQ(escaped("\x7f"), "\\x7f");
  EXPECT_EQ(escaped("sun at 250\xc2\xb0, caf\xc3\xa9"), "sun at 250\xc2\xb0, caf\xc3\xa9") << "printable UTF-8 as is";
  EXPECT_EQ(escaped("\xc2\x85"), "\\xc2\\x85") << "a C1 control (NEL: a newline on some terminals)";
  EXPECT_EQ(escaped("a\xe2\x80\xa8"
                    "b"),
            "a\\xe2\\x80\\xa8b")
      << "U+2028, the line separator";
  EXPECT_EQ(escaped("\xe2\x80\xae"
                    "evil"),
            "\\xe2\\x80\\xaeevil")
      << "U+202E reverses the text after it";
  EXPECT_EQ(escaped("\xc3"), "\\xc3") << "a truncated sequence";
  EXPECT_EQ(escaped("\xc0\xaf"), "\\xc0\\xaf") << "an overlong '/'";
  EXPECT_EQ(escaped("\xed\xa0\x80"), "\\xed\\xa0\\x80") << "a surrogate";
  EXPECT_EQ(escaped("\xf0\x9f\x8c\x85"), "\xf0\x9f\x8c\x85") << "U+1F305, four bytes";
  // An escaped text cannot pass for an escape: a literal "\x0a" in the input stays apart from a newline.
  EXPECT_EQ(escaped("\\x0a"), "\\\\x0a");
  EXPECT_NE(escaped("\\x0a"), escaped("\n"));
}

TEST(Escaped, ALongTextIsCutAtTheLimitWithItsLength) {
  const std::string long_text(1000, 'a');
  EXPECT_EQ(escaped(long_text, 10), "aaaaaaaaaa…(1000 bytes)");
  EXPECT_EQ(escaped(long_text).size(), 200u + std::string("…(1000 bytes)").size()) << "200 bytes by default";
  EXPECT_EQ(escaped("abc", 3), "abc") << "the limit is inclusive";
}

}  // namespace
}  // namespace zenith::core
