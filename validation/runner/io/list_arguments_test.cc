#include "validation/runner/io/list_arguments.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace phdslam::validation {
namespace {

using Seeds = std::vector<std::uint64_t>;

TEST(ParseSeedList, RangeSingleAndCommaLists) {
  EXPECT_EQ(ParseSeedList("1-5"), (Seeds{1, 2, 3, 4, 5}));
  EXPECT_EQ(ParseSeedList("7"), (Seeds{7}));
  EXPECT_EQ(ParseSeedList("0"), (Seeds{0}));
  EXPECT_EQ(ParseSeedList("3,1,10-12"), (Seeds{3, 1, 10, 11, 12}));
  EXPECT_EQ(ParseSeedList(" 4 - 5 , 9 "), (Seeds{4, 5, 9}));
  EXPECT_EQ(ParseSeedList("6-6"), (Seeds{6}));
  EXPECT_EQ(ParseSeedList("18446744073709551614-18446744073709551615"),
            (Seeds{18446744073709551614ULL, 18446744073709551615ULL}));
}

TEST(ParseSeedList, RejectsMalformedLists) {
  for (const char* bad : {"", " ", "a", "1-", "-3", "5-2", "1,,2", "1,", ",1", "1.5", "1-2-3", "+4",
                          "0x10", "18446744073709551616", "1,1", "1-3,2"}) {
    EXPECT_THROW(ParseSeedList(bad), std::invalid_argument) << "'" << bad << "'";
  }
}

TEST(ParseSeedList, ErrorNamesTheOffendingItem) {
  try {
    ParseSeedList("1,5-2");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("5-2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("reversed"), std::string::npos) << e.what();
  }
  try {
    ParseSeedList("1-3,2");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2 is listed twice"), std::string::npos) << e.what();
  }
}

TEST(ParseSeedList, RejectsHugeRanges) {
  EXPECT_THROW(ParseSeedList("0-1000000"), std::invalid_argument);
  EXPECT_EQ(ParseSeedList("1-1000000").size(), 1000000u);
  // The cap is on the whole list, not on each range.
  EXPECT_THROW(ParseSeedList("1-600000,2000001-2400001"), std::invalid_argument);
  EXPECT_THROW(ParseSeedList("1-1000000,0"), std::invalid_argument);
  EXPECT_EQ(ParseSeedList("1-100").size(), 100u);
}

TEST(ParseParticleList, PositiveCounts) {
  EXPECT_EQ(ParseParticleList("1,10,100"), (std::vector<int>{1, 10, 100}));
  EXPECT_EQ(ParseParticleList("5"), (std::vector<int>{5}));
  for (const char* bad : {"", "0", "-1", "1,,2", "x", "10,10", "99999999999"}) {
    EXPECT_THROW(ParseParticleList(bad), std::invalid_argument) << "'" << bad << "'";
  }
}

TEST(ParseParticleList, UpperBoundIsNamed) {
  EXPECT_EQ(ParseParticleList("100000"), (std::vector<int>{100000}));
  try {
    (void)ParseParticleList("10,100001");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("more than the 100000 particles"), std::string::npos)
        << e.what();
  }
}

TEST(ParseNameList, TrimsAndRejectsEmptyOrDuplicateNames) {
  EXPECT_EQ(ParseNameList("phd3, odometry", "estimators"),
            (std::vector<std::string>{"phd3", "odometry"}));
  EXPECT_THROW(ParseNameList("a,,b", "estimators"), std::invalid_argument);
  EXPECT_THROW(ParseNameList("a,a", "estimators"), std::invalid_argument);
  EXPECT_THROW(ParseNameList("", "estimators"), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::validation
