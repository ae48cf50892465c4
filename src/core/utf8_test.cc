#include "src/core/utf8.h"

#include <gtest/gtest.h>

#include <string>

namespace phdslam {
namespace {

TEST(Utf8, SequenceLengthFollowsTheWellFormedTable) {
  EXPECT_EQ(Utf8SequenceLength("a", 0), 1U);
  EXPECT_EQ(Utf8SequenceLength("\xc3\xa9", 0), 2U);          // U+00E9
  EXPECT_EQ(Utf8SequenceLength("\xe2\x82\xac", 0), 3U);      // U+20AC
  EXPECT_EQ(Utf8SequenceLength("\xf0\x9f\x98\x80", 0), 4U);  // U+1F600
  EXPECT_EQ(Utf8SequenceLength("\xf4\x8f\xbf\xbf", 0), 4U);  // U+10FFFF
  EXPECT_EQ(Utf8SequenceLength("\x80", 0), 0U);              // stray continuation byte
  EXPECT_EQ(Utf8SequenceLength("\xc0\xaf", 0), 0U);          // overlong '/'
  EXPECT_EQ(Utf8SequenceLength("\xe0\x80\xaf", 0), 0U);      // overlong '/'
  EXPECT_EQ(Utf8SequenceLength("\xed\xa0\x80", 0), 0U);      // surrogate U+D800
  EXPECT_EQ(Utf8SequenceLength("\xf4\x90\x80\x80", 0), 0U);  // above U+10FFFF
  EXPECT_EQ(Utf8SequenceLength("\xf5\x80\x80\x80", 0), 0U);
  EXPECT_EQ(Utf8SequenceLength("\xe2\x82", 0), 0U);  // cut short
  EXPECT_EQ(Utf8SequenceLength("\xe2\x28\xa1", 0), 0U);
}

TEST(Utf8, IsUtf8) {
  EXPECT_TRUE(IsUtf8(""));
  EXPECT_TRUE(IsUtf8("plain \xc3\xa9t\xc3\xa9"));
  EXPECT_FALSE(IsUtf8("caf\xe9"));
  EXPECT_FALSE(IsUtf8(std::string("a\xff", 2)));
}

TEST(Utf8, EscapeWritesEachInvalidByteAsHexAndKeepsTheRest) {
  EXPECT_EQ(EscapeNonUtf8("plain \xc3\xa9t\xc3\xa9"), "plain \xc3\xa9t\xc3\xa9");
  EXPECT_EQ(EscapeNonUtf8("caf\xe9"), "caf\\xE9");
  EXPECT_EQ(EscapeNonUtf8("\xff\xfexy\xe2\x82"), "\\xFF\\xFExy\\xE2\\x82");
  EXPECT_EQ(EscapeNonUtf8(std::string("\0\x80", 2)), std::string("\0\\x80", 5));
  EXPECT_TRUE(IsUtf8(EscapeNonUtf8("\xed\xa0\x80\xc0\xaf\xf8")));
}

}  // namespace
}  // namespace phdslam
