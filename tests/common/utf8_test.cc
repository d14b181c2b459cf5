#include "common/utf8.h"

#include <gtest/gtest.h>

#include <string>

#include "common/error.h"

namespace brdfrig {
namespace {

// The location of the first invalid byte, "line:column", or "" when the text is accepted.
std::string Where(const std::string& text) {
  try {
    RequireUtf8(text, "t");
    return "";
  } catch (const FileError& e) {
    return std::to_string(e.line()) + ":" + std::to_string(e.column());
  }
}

TEST(Utf8Test, WellFormedTextIsAccepted) {
  EXPECT_EQ(Where(""), "");
  EXPECT_EQ(Where("plain ascii\nsecond line"), "");
  EXPECT_EQ(Where("θh \u00e9 \u20ac \U0001F600 \U0010FFFF"), "");
}

TEST(Utf8Test, TheFirstBadByteIsLocatedByLineAndCharacter) {
  EXPECT_EQ(Where("ab\ncaf\xe9"), "2:4");       // Latin-1, not UTF-8
  EXPECT_EQ(Where("θ\xc3"), "1:2");             // truncated sequence
  EXPECT_EQ(Where("\xc0\xaf"), "1:1");          // overlong '/'
  EXPECT_EQ(Where("\xe0\x80\xaf"), "1:1");      // overlong, three bytes
  EXPECT_EQ(Where("x\xed\xa0\x80"), "1:2");     // a UTF-16 surrogate
  EXPECT_EQ(Where("\xf4\x90\x80\x80"), "1:1");  // beyond U+10FFFF
  EXPECT_EQ(Where("\x80"), "1:1");              // a lone continuation byte
  EXPECT_EQ(Where("\xe2\x82x"), "1:1");         // a continuation byte missing
}

TEST(Utf8Test, TheMessageNamesTheSourceAndTheByte) {
  try {
    RequireUtf8("ok\n\xff", "plan.yaml");
    FAIL() << "accepted";
  } catch (const FileError& e) {
    EXPECT_EQ(std::string(e.what()), "plan.yaml:2:1: not UTF-8 text (byte 0xff at offset 3)");
  }
}

}  // namespace
}  // namespace brdfrig
