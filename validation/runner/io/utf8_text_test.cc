#include "validation/runner/io/utf8_text.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace phdslam::validation {
namespace {

TEST(Utf8Text, AcceptsWellFormedText) {
  for (const char* good : {"", "ascii", "caf\xc3\xa9", "\xe2\x82\xac", "\xf0\x9f\x98\x80",
                           "\xed\x9f\xbf", "\xf4\x8f\xbf\xbf"}) {
    EXPECT_EQ(FirstInvalidUtf8Byte(good), std::nullopt) << good;
  }
}

TEST(Utf8Text, FindsTheFirstBadByte) {
  // A stray continuation byte, an overlong '/', a surrogate, a code point above U+10FFFF, a
  // truncated sequence at the end, a byte that never occurs in UTF-8.
  EXPECT_EQ(FirstInvalidUtf8Byte("ab\x80"), 2U);
  EXPECT_EQ(FirstInvalidUtf8Byte("\xc0\xaf"), 0U);
  EXPECT_EQ(FirstInvalidUtf8Byte("x\xe0\x80\xaf"), 1U);
  EXPECT_EQ(FirstInvalidUtf8Byte("\xed\xa0\x80"), 0U);
  EXPECT_EQ(FirstInvalidUtf8Byte("\xf4\x90\x80\x80"), 0U);
  EXPECT_EQ(FirstInvalidUtf8Byte("ok\xe2\x82"), 2U);
  EXPECT_EQ(FirstInvalidUtf8Byte("\xc3\xa9\xff"), 2U);
}

TEST(Utf8Text, ErrorNamesTheSourceLineColumnAndByte) {
  try {
    RequireUtf8("first\nsec\xb7nd\n", "f.yaml");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "f.yaml: line 2, column 4: not valid UTF-8 (byte 0xB7)");
  }
  EXPECT_NO_THROW(RequireUtf8("first\nsecond\n", "f.yaml"));
}

}  // namespace
}  // namespace phdslam::validation
