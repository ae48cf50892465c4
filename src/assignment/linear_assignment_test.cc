#include "src/assignment/linear_assignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "src/assignment/brute_force_assignments.h"
#include "src/core/random.h"

namespace phdslam::assignment {
namespace {

// Random cost matrix: integer costs in [0, 3] (many ties) or uniform reals, each entry forbidden
// with probability `forbidden_fraction`.
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

void ExpectValidAssignment(const Eigen::MatrixXd& cost, const Assignment& a) {
  ASSERT_EQ(static_cast<int>(a.row_to_col.size()), cost.rows());
  std::set<int> used;
  double sum = 0.0;
  for (int i = 0; i < cost.rows(); ++i) {
    const int j = a.row_to_col[i];
    ASSERT_GE(j, 0);
    ASSERT_LT(j, cost.cols());
    EXPECT_TRUE(used.insert(j).second) << "column " << j << " used twice";
    EXPECT_TRUE(std::isfinite(cost(i, j)));
    sum += cost(i, j);
  }
  EXPECT_EQ(a.cost, sum);
}

TEST(SolveLinearAssignment, HandComputedSquareCase) {
  Eigen::MatrixXd cost(3, 3);
  cost << 4, 1, 3, 2, 0, 5, 3, 2, 2;
  const auto a = SolveLinearAssignment(cost);
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->row_to_col, (std::vector<int>{1, 0, 2}));
  EXPECT_EQ(a->cost, 5.0);
}

TEST(SolveLinearAssignment, RectangularPrefersCheapColumnsAndAvoidsForbidden) {
  Eigen::MatrixXd cost(2, 4);
  cost << 5, kForbidden, 1, 7, kForbidden, 3, 1, 9;
  const auto a = SolveLinearAssignment(cost);
  ASSERT_TRUE(a.has_value());
  // Options: (2, 1) = 4, (0, 2) = 6, (0, 1) = 8, ...
  EXPECT_EQ(a->row_to_col, (std::vector<int>{2, 1}));
  EXPECT_EQ(a->cost, 4.0);
}

TEST(SolveLinearAssignment, InfeasibleCasesGiveNullopt) {
  Eigen::MatrixXd all_forbidden_row(2, 3);
  all_forbidden_row << 1, 2, 3, kForbidden, kForbidden, kForbidden;
  EXPECT_FALSE(SolveLinearAssignment(all_forbidden_row).has_value());
  // Two rows that can only use the same column.
  Eigen::MatrixXd shared_column(2, 3);
  shared_column << kForbidden, 1, kForbidden, kForbidden, 2, kForbidden;
  EXPECT_FALSE(SolveLinearAssignment(shared_column).has_value());
}

TEST(SolveLinearAssignment, EmptyMatrixGivesEmptyAssignment) {
  const auto a = SolveLinearAssignment(Eigen::MatrixXd(0, 3));
  ASSERT_TRUE(a.has_value());
  EXPECT_TRUE(a->row_to_col.empty());
  EXPECT_EQ(a->cost, 0.0);
}

TEST(SolveLinearAssignment, RejectsBadInput) {
  EXPECT_THROW(SolveLinearAssignment(Eigen::MatrixXd::Zero(3, 2)), std::invalid_argument);
  Eigen::MatrixXd nan_cost = Eigen::MatrixXd::Zero(2, 2);
  nan_cost(1, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SolveLinearAssignment(nan_cost), std::invalid_argument);
  Eigen::MatrixXd minus_inf = Eigen::MatrixXd::Zero(2, 2);
  minus_inf(0, 1) = -std::numeric_limits<double>::infinity();
  EXPECT_THROW(SolveLinearAssignment(minus_inf), std::invalid_argument);
}

TEST(SolveLinearAssignment, MatchesBruteForceOnRandomMatrices) {
  int feasible = 0;
  int infeasible = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    RandomStream rng(DeriveSeed(HashName("linear_assignment_test"), trial));
    const int rows = 1 + static_cast<int>(rng.Uniform(0.0, 6.0));
    const int cols = rows + static_cast<int>(rng.Uniform(0.0, 4.0));
    const bool integer = trial % 2 == 0;
    const double forbidden_fraction = (trial % 3) * 0.25;
    const Eigen::MatrixXd cost = RandomCost(rng, rows, cols, integer, forbidden_fraction);
    const auto all = testing::BruteForceAssignments(cost);
    const auto a = SolveLinearAssignment(cost);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << "\n" << cost);
    if (all.empty()) {
      EXPECT_FALSE(a.has_value());
      ++infeasible;
      continue;
    }
    ++feasible;
    ASSERT_TRUE(a.has_value());
    ExpectValidAssignment(cost, *a);
    EXPECT_NEAR(a->cost, all.front().cost, 1e-9);
  }
  EXPECT_GT(feasible, 1000);
  EXPECT_GT(infeasible, 50);
}

TEST(SolveLinearAssignment, MatchesBruteForceOnLargerRectangularMatrices) {
  for (int trial = 0; trial < 20; ++trial) {
    RandomStream rng(DeriveSeed(HashName("linear_assignment_test_large"), trial));
    const Eigen::MatrixXd cost = RandomCost(rng, 6, 9, trial % 2 == 0, 0.1);
    const auto all = testing::BruteForceAssignments(cost);
    const auto a = SolveLinearAssignment(cost);
    ASSERT_EQ(a.has_value(), !all.empty());
    if (!a) continue;
    ExpectValidAssignment(cost, *a);
    EXPECT_NEAR(a->cost, all.front().cost, 1e-9);
  }
}

// A cost matrix shaped like the filters' association costs: `rows` landmarks, `measurements`
// measurement columns (each landmark gated to a few, the rest forbidden), then one private
// missed-detection column per landmark. Landmark i is usually cheapest at measurement i, so most
// matrices have distinct row minima, and some share a measurement or tie within the margin.
Eigen::MatrixXd FilterShapedCost(RandomStream& rng, int rows, int measurements) {
  Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(rows, measurements + rows, kForbidden);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < measurements; ++j) {
      const bool near = j == i % measurements;
      if (near || rng.Uniform() < 0.3) cost(i, j) = (near ? 0.0 : 4.0) + rng.Uniform(0.0, 6.0);
    }
    cost(i, measurements + i) = 3.0 + rng.Uniform(0.0, 4.0);
    if (rng.Uniform() < 0.05) cost(i, measurements + i) = cost(i, i % measurements) + 1e-13;
  }
  return cost;
}

TEST(SolveLinearAssignment, RowMinimaShortcutGivesThePathSearchResultBitForBit) {
  int distinct_minima = 0;
  int shared_or_close = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    RandomStream rng(DeriveSeed(HashName("linear_assignment_shortcut"), trial));
    const int rows = 1 + static_cast<int>(rng.Uniform(0.0, 12.0));
    const int measurements = 1 + static_cast<int>(rng.Uniform(0.0, 15.0));
    const Eigen::MatrixXd cost = FilterShapedCost(rng, rows, measurements);
    const auto fast = SolveLinearAssignment(cost);
    const auto paths = SolveLinearAssignmentByPaths(cost);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << "\n" << cost);
    ASSERT_EQ(fast.has_value(), paths.has_value());
    if (!fast) continue;
    EXPECT_EQ(fast->row_to_col, paths->row_to_col);
    EXPECT_EQ(fast->cost, paths->cost);  // exact: the same entries summed in the same order
    std::set<int> minima;
    for (int i = 0; i < rows; ++i) {
      Eigen::Index j = 0;
      cost.row(i).minCoeff(&j);
      minima.insert(static_cast<int>(j));
    }
    (static_cast<int>(minima.size()) == rows ? distinct_minima : shared_or_close)++;
  }
  // Both kinds occur, so both the shortcut and the path search are compared.
  EXPECT_GT(distinct_minima, 1000);
  EXPECT_GT(shared_or_close, 500);
}

TEST(SolveLinearAssignment, RowMinimaShortcutStillRejectsBadInput) {
  Eigen::MatrixXd cost(2, 3);
  cost << 0.0, 5.0, 5.0, 5.0, 0.0, 5.0;
  cost(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SolveLinearAssignment(cost), std::invalid_argument);
  cost(1, 2) = -std::numeric_limits<double>::infinity();
  EXPECT_THROW(SolveLinearAssignment(cost), std::invalid_argument);
  EXPECT_THROW(SolveLinearAssignment(Eigen::MatrixXd::Zero(3, 2)), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::assignment
