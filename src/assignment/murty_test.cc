#include "src/assignment/murty.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

#include "src/assignment/brute_force_assignments.h"
#include "src/core/random.h"

namespace phdslam::assignment {
namespace {

Eigen::MatrixXd RandomCost(RandomStream& rng, int rows, int cols, bool integer,
                           double forbidden_fraction) {
  Eigen::MatrixXd cost(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      cost(i, j) = integer ? std::floor(rng.Uniform(0.0, 4.0)) : rng.Uniform(-5.0, 10.0);
      if (rng.Uniform() < forbidden_fraction) cost(i, j) = kForbidden;
    }
  }
  return cost;
}

// Checks `ranked` against the brute-force list `expected` (sorted): same length and costs; every
// assignment valid and distinct; for each cost value that the ranking covers completely the same
// set of assignments, and for the last (possibly cut) value a subset of the tied ones.
void ExpectSameRanking(const Eigen::MatrixXd& cost, const std::vector<Assignment>& ranked,
                       const std::vector<Assignment>& expected, double tol) {
  ASSERT_EQ(ranked.size(), expected.size());
  std::set<std::vector<int>> seen;
  for (std::size_t t = 0; t < ranked.size(); ++t) {
    EXPECT_NEAR(ranked[t].cost, expected[t].cost, tol) << "hypothesis " << t;
    if (t > 0) {
      EXPECT_GE(ranked[t].cost, ranked[t - 1].cost - tol);
    }
    ASSERT_EQ(static_cast<int>(ranked[t].row_to_col.size()), cost.rows());
    double sum = 0.0;
    std::set<int> used;
    for (int i = 0; i < cost.rows(); ++i) {
      const int j = ranked[t].row_to_col[i];
      ASSERT_TRUE(j >= 0 && j < cost.cols());
      EXPECT_TRUE(used.insert(j).second);
      sum += cost(i, j);
    }
    EXPECT_TRUE(std::isfinite(sum));
    EXPECT_EQ(ranked[t].cost, sum);
    EXPECT_TRUE(seen.insert(ranked[t].row_to_col).second) << "duplicate hypothesis " << t;
  }
  if (ranked.empty()) return;
  // Group by cost (costs equal within tol are ties).
  const double last_cost = expected.back().cost;
  std::set<std::vector<int>> ranked_complete, expected_complete, ranked_last;
  for (const auto& a : ranked) {
    (a.cost < last_cost - tol ? ranked_complete : ranked_last).insert(a.row_to_col);
  }
  for (const auto& a : expected) {
    if (a.cost < last_cost - tol) expected_complete.insert(a.row_to_col);
  }
  EXPECT_EQ(ranked_complete, expected_complete);
  // The last cost group: every ranked assignment must be one of the tied brute-force ones.
  const auto all = testing::BruteForceAssignments(cost);
  std::set<std::vector<int>> all_tied_last;
  for (const auto& a : all) {
    if (std::abs(a.cost - last_cost) <= tol) all_tied_last.insert(a.row_to_col);
  }
  for (const auto& a : ranked_last) EXPECT_TRUE(all_tied_last.count(a)) << "not a tie of the last";
}

std::vector<Assignment> Truncate(std::vector<Assignment> all, int k) {
  if (static_cast<int>(all.size()) > k) all.resize(k);
  return all;
}

// The early stop of docs/algorithms/phd-slam.md section 4.4 applied to the brute-force list.
std::vector<Assignment> TruncateByGap(const std::vector<Assignment>& all, int k, double gap) {
  std::vector<Assignment> kept;
  for (const auto& a : all) {
    if (static_cast<int>(kept.size()) == k) break;
    if (!kept.empty() && a.cost - kept.front().cost > gap) break;
    kept.push_back(a);
  }
  return kept;
}

TEST(MurtyKBest, HandComputedRanking) {
  Eigen::MatrixXd cost(2, 3);
  cost << 1, 2, 10, 3, 1, kForbidden;
  // Assignments: (0,1)=2, (1,0)=5, (2,0)=13, (2,1)=11; forbidden (0,2), (1,2).
  const auto ranked = MurtyKBest(cost, 10);
  ASSERT_EQ(ranked.size(), 4u);
  EXPECT_EQ(ranked[0].row_to_col, (std::vector<int>{0, 1}));
  EXPECT_EQ(ranked[1].row_to_col, (std::vector<int>{1, 0}));
  EXPECT_EQ(ranked[2].row_to_col, (std::vector<int>{2, 1}));
  EXPECT_EQ(ranked[3].row_to_col, (std::vector<int>{2, 0}));
  EXPECT_EQ(ranked[0].cost, 2.0);
  EXPECT_EQ(ranked[1].cost, 5.0);
  EXPECT_EQ(ranked[2].cost, 11.0);
  EXPECT_EQ(ranked[3].cost, 13.0);
  // Gap 3: 5 - 2 <= 3 is kept, 11 - 2 > 3 stops and is discarded.
  const auto stopped = MurtyKBest(cost, 10, 3.0);
  ASSERT_EQ(stopped.size(), 2u);
  EXPECT_EQ(stopped[1].cost, 5.0);
}

TEST(MurtyKBest, EdgeCases) {
  Eigen::MatrixXd all_forbidden_row(2, 3);
  all_forbidden_row << 1, 2, 3, kForbidden, kForbidden, kForbidden;
  EXPECT_TRUE(MurtyKBest(all_forbidden_row, 5).empty());
  EXPECT_TRUE(MurtyKBest(all_forbidden_row, 5, 1.0).empty());
  EXPECT_TRUE(MurtyKBest(Eigen::MatrixXd::Ones(2, 2), 0).empty());
  const auto empty_rows = MurtyKBest(Eigen::MatrixXd(0, 4), 3);
  ASSERT_EQ(empty_rows.size(), 1u);
  EXPECT_TRUE(empty_rows[0].row_to_col.empty());
  EXPECT_EQ(empty_rows[0].cost, 0.0);
  // A 1x1 problem has exactly one assignment.
  EXPECT_EQ(MurtyKBest(Eigen::MatrixXd::Constant(1, 1, 4.0), 50).size(), 1u);
  EXPECT_THROW(MurtyKBest(Eigen::MatrixXd::Zero(3, 2), 2), std::invalid_argument);
  EXPECT_THROW(MurtyKBest(Eigen::MatrixXd::Zero(2, 2), -1), std::invalid_argument);
  EXPECT_THROW(MurtyKBest(Eigen::MatrixXd::Zero(2, 2), 2, std::nan("")), std::invalid_argument);
  Eigen::MatrixXd nan_cost = Eigen::MatrixXd::Zero(2, 2);
  nan_cost(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(MurtyKBest(nan_cost, 2), std::invalid_argument);
}

TEST(MurtyKBest, AllTiedCostsEnumerateEveryAssignmentOnce) {
  const Eigen::MatrixXd cost = Eigen::MatrixXd::Zero(3, 5);  // 5 * 4 * 3 = 60 assignments
  const auto ranked = MurtyKBest(cost, 1000);
  ASSERT_EQ(ranked.size(), 60u);
  std::set<std::vector<int>> distinct;
  for (const auto& a : ranked) distinct.insert(a.row_to_col);
  EXPECT_EQ(distinct.size(), 60u);
}

TEST(MurtyKBest, MatchesBruteForceOnRandomSmallMatrices) {
  const int ks[] = {1, 2, 3, 7, 20, 50, 100000};
  int infeasible = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    RandomStream rng(DeriveSeed(HashName("murty_test"), trial));
    const int rows = 1 + static_cast<int>(rng.Uniform(0.0, 5.0));
    const int cols = rows + static_cast<int>(rng.Uniform(0.0, std::min(4, 9 - rows)));
    const bool integer = trial % 2 == 0;
    const double forbidden_fraction = (trial % 3) * 0.25;
    const Eigen::MatrixXd cost = RandomCost(rng, rows, cols, integer, forbidden_fraction);
    const auto all = testing::BruteForceAssignments(cost);
    if (all.empty()) ++infeasible;
    const double tol = integer ? 0.0 : 1e-9;
    for (const int k : ks) {
      SCOPED_TRACE(::testing::Message() << "trial " << trial << " k " << k << "\n" << cost);
      ExpectSameRanking(cost, MurtyKBest(cost, k), Truncate(all, k), tol);
    }
  }
  EXPECT_GT(infeasible, 20);
}

TEST(MurtyKBest, EarlyStopMatchesBruteForceTruncatedByGap) {
  for (int trial = 0; trial < 1000; ++trial) {
    RandomStream rng(DeriveSeed(HashName("murty_gap_test"), trial));
    const int rows = 1 + static_cast<int>(rng.Uniform(0.0, 5.0));
    const int cols = rows + static_cast<int>(rng.Uniform(0.0, std::min(4, 9 - rows)));
    const bool integer = trial % 2 == 0;
    const Eigen::MatrixXd cost = RandomCost(rng, rows, cols, integer, (trial % 3) * 0.2);
    const auto all = testing::BruteForceAssignments(cost);
    const double tol = integer ? 0.0 : 1e-9;
    // Integer gaps hit ties of the gap rule exactly (cost - best == gap is kept).
    for (const double gap : {0.0, 1.0, 2.0, 2.5, 6.9078, 1e9}) {
      for (const int k : {1, 2, 5, 50}) {
        SCOPED_TRACE(::testing::Message()
                     << "trial " << trial << " gap " << gap << " k " << k << "\n"
                     << cost);
        ExpectSameRanking(cost, MurtyKBest(cost, k, gap), TruncateByGap(all, k, gap), tol);
      }
    }
  }
}

TEST(MurtyKBest, MatchesBruteForceOnFilterSizedMatrices) {
  // Shapes like the PHD-SLAM 3.0 cost matrix: components x (measurements + components).
  const std::pair<int, int> shapes[] = {{3, 9}, {4, 10}, {6, 10}};
  for (int trial = 0; trial < 12; ++trial) {
    RandomStream rng(DeriveSeed(HashName("murty_filter_sized_test"), trial));
    const auto [rows, cols] = shapes[trial % 3];
    const bool integer = trial % 2 == 0;
    const Eigen::MatrixXd cost = RandomCost(rng, rows, cols, integer, 0.3);
    const auto all = testing::BruteForceAssignments(cost);
    const double tol = integer ? 0.0 : 1e-9;
    SCOPED_TRACE(::testing::Message() << "trial " << trial << "\n" << cost);
    ExpectSameRanking(cost, MurtyKBest(cost, 50), Truncate(all, 50), tol);
    ExpectSameRanking(cost, MurtyKBest(cost, 50, 6.9078), TruncateByGap(all, 50, 6.9078), tol);
  }
}

}  // namespace
}  // namespace phdslam::assignment
