#include "validation/runner/io/results_io.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/test_temp_dir.h"

namespace phdslam::validation {
namespace {

TEST(FormatNumber, TenSignificantDigitsAndEmptyForUnknown) {
  EXPECT_EQ(FormatNumber(1.0), "1");
  EXPECT_EQ(FormatNumber(0.1), "0.1");
  EXPECT_EQ(FormatNumber(3.14159265358979), "3.141592654");
  EXPECT_EQ(FormatNumber(-2.5e-12), "-2.5e-12");
  EXPECT_EQ(FormatNumber(254.2134567891), "254.2134568");
  EXPECT_EQ(FormatNumber(std::numeric_limits<double>::quiet_NaN()), "");
  EXPECT_EQ(FormatNumber(std::numeric_limits<double>::infinity()), "");
  EXPECT_EQ(FormatNumber(std::optional<double>()), "");
  EXPECT_EQ(FormatNumber(std::optional<double>(2.0)), "2");
}

TEST(FormatNumber, SameTextAsPrintfTenSignificantDigits) {
  // Results files written before FormatNumber used std::to_chars held snprintf's "%.10g": the
  // two must agree on every finite double, extremes and subnormals included.
  std::mt19937_64 bits_source(20261125);
  std::vector<double> values = {0.0,
                                -0.0,
                                1e-5,
                                1e-4,
                                9999999999.5,
                                99999.999995,
                                1e10,
                                5e-324,
                                2.2250738585072014e-308,
                                1.7976931348623157e308};
  for (int i = 0; i < 200000; ++i) {
    const std::uint64_t bits = bits_source();
    double v = 0.0;
    std::memcpy(&v, &bits, sizeof v);
    values.push_back(v);
    values.push_back(std::ldexp(static_cast<double>(bits >> 11) / 9007199254740992.0 - 0.5,
                                static_cast<int>(bits % 120) - 60));
  }
  int compared = 0;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    std::array<char, 64> expected{};
    const int n = std::snprintf(expected.data(), expected.size(), "%.10g", v);
    ASSERT_EQ(FormatNumber(v), std::string(expected.data(), static_cast<std::size_t>(n))) << v;
    ++compared;
  }
  EXPECT_GT(compared, 390000);
}

TEST(CsvRow, JoinsCellsAndRejectsSpecialCharacters) {
  EXPECT_EQ(CsvRow({"a", "", "1.5"}), "a,,1.5\n");
  EXPECT_THROW(CsvRow({"a,b"}), std::invalid_argument);
  EXPECT_THROW(CsvRow({"a\n"}), std::invalid_argument);
}

TEST(WriteFileAtomically, ReplacesTheFileAndLeavesNoTemporary) {
  const auto dir = datasets::testing::FreshTestDir();
  WriteFileAtomically(dir / "f.txt", "first");
  WriteFileAtomically(dir / "f.txt", "second");
  EXPECT_EQ(ReadTextFile(dir / "f.txt"), "second");
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
}

TEST(WriteFileAtomically, AFailingWriterLeavesTheOldFile) {
  const auto dir = datasets::testing::FreshTestDir();
  WriteFileAtomically(dir / "f.txt", "old");
  EXPECT_THROW(WriteFileAtomically(dir / "f.txt",
                                   [](const std::filesystem::path& temp) {
                                     WriteFileAtomically(temp, "partial");
                                     throw std::runtime_error("writer failed");
                                   }),
               std::runtime_error);
  EXPECT_EQ(ReadTextFile(dir / "f.txt"), "old");
  EXPECT_FALSE(std::filesystem::exists(dir / "f.txt.tmp-0"));
}

TEST(WriteFileAtomically, ReportsAMissingFolder) {
  const auto dir = datasets::testing::FreshTestDir();
  EXPECT_THROW(WriteFileAtomically(dir / "missing" / "f.txt", "x"), std::runtime_error);
  EXPECT_THROW(ReadTextFile(dir / "missing.txt"), std::runtime_error);
}

// A byte-order mark before the header is skipped: the first column keeps its name.
TEST(ParseCsv, SkipsAByteOrderMark) {
  const CsvTable t = ParseCsv(
      "\xEF\xBB\xBF"
      "estimator,seed\nphd3,1\n",
      "t.csv");
  EXPECT_EQ(t.FindColumn("estimator"), std::optional<std::size_t>(0));
  EXPECT_EQ(t.rows.size(), 1u);
}

TEST(ParseCsv, ReadsHeaderAndRowsAndFindsColumns) {
  const CsvTable t = ParseCsv("a,b,c\n1,,3\r\n4,5,6\n\n", "t.csv");
  EXPECT_EQ(t.header, std::vector<std::string>({"a", "b", "c"}));
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0], std::vector<std::string>({"1", "", "3"}));
  EXPECT_EQ(t.rows[1][2], "6");
  EXPECT_EQ(t.FindColumn("c"), 2u);
  EXPECT_FALSE(t.FindColumn("d").has_value());
  EXPECT_EQ(ParseCsv("x\n", "t").rows.size(), 0u);
}

TEST(ParseCsv, RejectsRaggedRowsAndEmptyText) {
  try {
    ParseCsv("a,b\n1,2\n3\n", "t.csv");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("t.csv:3:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ParseCsv("", "t.csv"), std::runtime_error);
}

}  // namespace
}  // namespace phdslam::validation
