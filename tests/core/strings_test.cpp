// core::escaped (core/strings.h): what every peer-supplied string becomes
// before it is logged (issue 30: an OSC address with a newline once forged a
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
  EXPECT_EQ(escaped("\xc3\xa9"), "\\xc3\\xa9") << "UTF-8 bytes too: the log stays ASCII";
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
