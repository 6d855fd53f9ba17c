// Tests of support/printable.h: what a terminal would act on is escaped, text is kept.
#include "vgroove/support/printable.h"

#include <gtest/gtest.h>

#include <string>

namespace vgroove::support {
namespace {

TEST(Printable, KeepsPrintableTextAndUtf8) {
  EXPECT_EQ(printable("data/suites/x.json: /rays = 5"), "data/suites/x.json: /rays = 5");
  EXPECT_EQ(printable("caf\xc3\xa9 \xe6\xbc\xa2 \xf0\x9f\x98\x80"), "caf\xc3\xa9 \xe6\xbc\xa2 \xf0\x9f\x98\x80");
}

TEST(Printable, EscapesControlsOnOneLine) {
  EXPECT_EQ(printable("a\nb\tc\rd"), "a\\nb\\tc\\rd");
  EXPECT_EQ(printable(std::string("e\x1b[31mf\0g\x7f", 10)), "e\\x1b[31mf\\x00g\\x7f");
  EXPECT_EQ(printable("\xc2\x85"), "\\u{0085}");  // C1 NEL
  EXPECT_EQ(printable("\xc2\x9b"), "\\u{009B}");  // C1 CSI
}

TEST(Printable, EscapesBidirectionalControlsAndSeparators) {
  EXPECT_EQ(printable("a\xe2\x80\xae"
                      "b"),
            "a\\u{202E}b");  // RIGHT-TO-LEFT OVERRIDE
  EXPECT_EQ(printable("\xe2\x81\xa6"
                      "x\xe2\x81\xa9"),
            "\\u{2066}x\\u{2069}");
  EXPECT_EQ(printable("\xe2\x80\x8f"), "\\u{200F}");
  EXPECT_EQ(printable("\xd8\x9c"), "\\u{061C}");
  EXPECT_EQ(printable("\xe2\x80\xa8"), "\\u{2028}");
}

TEST(Printable, EscapesBytesThatAreNotUtf8) {
  EXPECT_EQ(printable("\xff"), "\\xff");
  EXPECT_EQ(printable("\xc3"), "\\xc3");                             // truncated sequence
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");                    // overlong "/"
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");           // a surrogate
  EXPECT_EQ(printable("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");  // past U+10FFFF
}

}  // namespace
}  // namespace vgroove::support
