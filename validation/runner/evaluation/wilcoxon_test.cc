#include "validation/runner/evaluation/wilcoxon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace phdslam::validation {
namespace {

// Reference p-values: scipy 1.10, scipy.stats.wilcoxon(d, method=..., correction=True).

TEST(WilcoxonSignedRank, ExactByHandForEightDifferences) {
  // |d| ranks 1..8; the negative differences -3 and -7 have ranks 3 and 7: W- = 10, W+ = 26.
  // P(W <= 10) for n = 8 is 40 / 256 (subsets of 1..8 with sum <= 10), so p = 0.3125.
  const WilcoxonResult r = WilcoxonSignedRank({1.5, 2, -3, 4, 5, 6, -7, 8});
  EXPECT_EQ(r.method, WilcoxonMethod::kExact);
  EXPECT_EQ(r.n, 8u);
  EXPECT_EQ(r.n_nonzero, 8u);
  EXPECT_DOUBLE_EQ(r.w_minus, 10.0);
  EXPECT_DOUBLE_EQ(r.w_plus, 26.0);
  EXPECT_DOUBLE_EQ(r.statistic, 10.0);
  EXPECT_FALSE(r.z.has_value());
  ASSERT_TRUE(r.p_value.has_value());
  EXPECT_DOUBLE_EQ(*r.p_value, 0.3125);
}

TEST(WilcoxonSignedRank, ExactMatchesScipy) {
  EXPECT_DOUBLE_EQ(*WilcoxonSignedRank({0.3, -0.1, 0.5, 0.7, 1.1}).p_value, 0.125);
  // All positive: W- = 0, p = 2 / 2^6.
  const WilcoxonResult all_positive = WilcoxonSignedRank({1, 2, 3, 4, 5, 6});
  EXPECT_DOUBLE_EQ(all_positive.statistic, 0.0);
  EXPECT_DOUBLE_EQ(*all_positive.p_value, 0.03125);
  // n = 25 is the largest exact case.
  const std::vector<double> d25 = {1,  2,  -3, 4,  5,  6,  -7, 8,  9,  10, 11, -12, 13,
                                   14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25};
  const WilcoxonResult r25 = WilcoxonSignedRank(d25);
  EXPECT_EQ(r25.method, WilcoxonMethod::kExact);
  EXPECT_NEAR(*r25.p_value, 3.1948089599609375e-05, 1e-15);
}

TEST(WilcoxonSignedRank, NormalApproximationBeyondTheExactLimit) {
  std::vector<double> d26 = {1,  2,  -3, 4,  5,  6,  -7, 8,  9,  10, 11, -12, 13,
                             14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25,  26};
  const WilcoxonResult r = WilcoxonSignedRank(d26);
  EXPECT_EQ(r.method, WilcoxonMethod::kNormal);
  ASSERT_TRUE(r.z.has_value());
  EXPECT_LT(*r.z, 0.0);
  EXPECT_NEAR(*r.p_value, 0.00010195544965807872, 1e-12);
}

TEST(WilcoxonSignedRank, ZerosAreDroppedAndTiesCorrected) {
  // Two zeros (dropped), ties among |d| = 1 and |d| = 2: normal approximation with the tie term.
  const WilcoxonResult r = WilcoxonSignedRank({1, 2, -2, 4, 5, 0, 6, -7, 8, 2, 0, -1});
  EXPECT_EQ(r.method, WilcoxonMethod::kNormal);
  EXPECT_EQ(r.n, 12u);
  EXPECT_EQ(r.n_nonzero, 10u);
  EXPECT_DOUBLE_EQ(r.statistic, 14.5);  // ranks: |1| 1.5, |2| 4, |7| 9 -> W- = 1.5+4+9
  EXPECT_DOUBLE_EQ(r.w_plus + r.w_minus, 55.0);
  EXPECT_NEAR(*r.p_value, 0.20115248605459868, 1e-12);
}

TEST(WilcoxonSignedRank, ThirtyDifferencesWithATieMatchScipy) {
  const std::vector<double> d = {2.441,  -2.156, 0.818, -0.168, -0.053, 0.184,  -1.62,  0.168,
                                 -0.465, 3.723,  0.626, 0.047,  0.119,  -0.268, -0.655, 0.009,
                                 0.882,  0.161,  1.358, 0.2,    0.424,  1.946,  0.945,  -0.105,
                                 0.217,  0.941,  2.335, 0.13,   0.156,  1.402};
  const WilcoxonResult r = WilcoxonSignedRank(d);
  EXPECT_EQ(r.method, WilcoxonMethod::kNormal);
  EXPECT_DOUBLE_EQ(r.statistic, 116.5);
  EXPECT_NEAR(*r.p_value, 0.01751541180446558, 1e-12);
}

TEST(WilcoxonSignedRank, SmallSampleWithTiesUsesTheApproximation) {
  const WilcoxonResult r = WilcoxonSignedRank({1, -1, 2, 3});
  EXPECT_EQ(r.method, WilcoxonMethod::kNormal);
  EXPECT_DOUBLE_EQ(r.statistic, 1.5);
  EXPECT_NEAR(*r.p_value, 0.2692941367197367, 1e-12);
}

TEST(WilcoxonSignedRank, AllZeroDifferencesGiveNoTest) {
  const WilcoxonResult r = WilcoxonSignedRank({0.0, 0.0, 0.0});
  EXPECT_EQ(r.method, WilcoxonMethod::kNone);
  EXPECT_EQ(r.n, 3u);
  EXPECT_EQ(r.n_nonzero, 0u);
  EXPECT_FALSE(r.p_value.has_value());
  EXPECT_EQ(WilcoxonSignedRank({}).method, WilcoxonMethod::kNone);
}

TEST(WilcoxonSignedRank, RejectsNonFiniteDifferences) {
  EXPECT_THROW(WilcoxonSignedRank({1.0, std::numeric_limits<double>::quiet_NaN()}),
               std::invalid_argument);
  EXPECT_THROW(WilcoxonSignedRank({std::numeric_limits<double>::infinity()}),
               std::invalid_argument);
}

TEST(Median, OddEvenAndEmpty) {
  EXPECT_DOUBLE_EQ(Median({3, 1, 2}), 2.0);
  EXPECT_DOUBLE_EQ(Median({4, 1, 3, 2}), 2.5);
  EXPECT_DOUBLE_EQ(Median({-1}), -1.0);
  EXPECT_THROW(Median({}), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::validation
