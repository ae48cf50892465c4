// Test helper: every feasible assignment of a small cost matrix, by exhaustive enumeration.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "src/assignment/linear_assignment.h"

namespace phdslam::assignment::testing {

/// All assignments of every row to a distinct column with only finite entries, sorted by cost
/// (ties by row_to_col). Costs are summed in row order, as the solvers do.
inline std::vector<Assignment> BruteForceAssignments(const Eigen::MatrixXd& cost) {
  const int rows = static_cast<int>(cost.rows());
  const int cols = static_cast<int>(cost.cols());
  std::vector<Assignment> all;
  std::vector<int> current(rows, -1);
  std::vector<char> used(cols, 0);
  const auto recurse = [&](const auto& self, int row) -> void {
    if (row == rows) {
      Assignment a{current, 0.0};
      for (int i = 0; i < rows; ++i) a.cost += cost(i, current[i]);
      all.push_back(a);
      return;
    }
    for (int j = 0; j < cols; ++j) {
      if (used[j] || !std::isfinite(cost(row, j))) continue;
      used[j] = 1;
      current[row] = j;
      self(self, row + 1);
      used[j] = 0;
    }
  };
  recurse(recurse, 0);
  std::sort(all.begin(), all.end(), [](const Assignment& a, const Assignment& b) {
    if (a.cost != b.cost) return a.cost < b.cost;
    return a.row_to_col < b.row_to_col;
  });
  return all;
}

}  // namespace phdslam::assignment::testing
