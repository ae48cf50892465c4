#include "src/assignment/linear_assignment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "src/assignment/shortest_augmenting_path.h"

namespace phdslam::assignment {

void ValidateCostMatrix(const Eigen::MatrixXd& cost, const char* caller) {
  if (cost.rows() > cost.cols()) {
    throw std::invalid_argument(std::string(caller) + ": cost matrix has " +
                                std::to_string(cost.rows()) + " rows and " +
                                std::to_string(cost.cols()) + " columns; expected rows <= cols");
  }
  for (Eigen::Index j = 0; j < cost.cols(); ++j) {
    for (Eigen::Index i = 0; i < cost.rows(); ++i) {
      const double c = cost(i, j);
      if (std::isnan(c) || c == -std::numeric_limits<double>::infinity()) {
        throw std::invalid_argument(std::string(caller) + ": cost(" + std::to_string(i) + ", " +
                                    std::to_string(j) + ") is " + std::to_string(c) +
                                    "; expected a finite value or +inf (forbidden)");
      }
    }
  }
}

namespace {

/// Each row's cheapest column into `row_to_col`, when these columns are distinct, each row's
/// cheapest entry is finite and below the row's others by kRowMinimumMargin times the largest
/// finite magnitude in the matrix, and no entry is NaN or -inf; false otherwise (the path search
/// then decides, or ValidateCostMatrix names the bad entry).
bool DistinctClearRowMinima(const Eigen::MatrixXd& cost, std::vector<int>& row_to_col) {
  const double infinity = std::numeric_limits<double>::infinity();
  const Eigen::Index rows = cost.rows();
  const Eigen::Index cols = cost.cols();
  if (rows > cols) return false;
  row_to_col.assign(static_cast<std::size_t>(rows), -1);
  std::vector<char> taken(static_cast<std::size_t>(cols), 0);
  double largest = 0.0;         // the largest finite magnitude
  double narrowest = infinity;  // the smallest gap between a row's two cheapest entries
  for (Eigen::Index i = 0; i < rows; ++i) {
    double best = infinity;
    double second = infinity;
    Eigen::Index best_col = -1;
    for (Eigen::Index j = 0; j < cols; ++j) {
      const double c = cost(i, j);
      if (!(c > -infinity)) return false;  // NaN or -inf
      if (c < infinity) largest = std::max(largest, std::abs(c));
      if (c < best) {
        second = best;
        best = c;
        best_col = j;
      } else if (c < second) {
        second = c;
      }
    }
    if (best_col < 0 || taken[static_cast<std::size_t>(best_col)] != 0) return false;
    taken[static_cast<std::size_t>(best_col)] = 1;
    row_to_col[static_cast<std::size_t>(i)] = static_cast<int>(best_col);
    narrowest = std::min(narrowest, second - best);
  }
  return narrowest > kRowMinimumMargin * largest;
}

}  // namespace

std::optional<Assignment> SolveLinearAssignment(const Eigen::MatrixXd& cost) {
  Assignment result;
  if (DistinctClearRowMinima(cost, result.row_to_col)) {
    for (int row = 0; row < cost.rows(); ++row) result.cost += cost(row, result.row_to_col[row]);
    return result;
  }
  return SolveLinearAssignmentByPaths(cost);
}

std::optional<Assignment> SolveLinearAssignmentByPaths(const Eigen::MatrixXd& cost) {
  ValidateCostMatrix(cost, "SolveLinearAssignment");
  ShortestAugmentingPath solver;
  solver.Reset(cost);
  for (int row = 0; row < solver.rows(); ++row) {
    if (!solver.AugmentToFreeColumn(row)) return std::nullopt;
  }
  Assignment result;
  result.row_to_col.assign(solver.col_for_row.begin(), solver.col_for_row.end());
  for (int row = 0; row < solver.rows(); ++row) result.cost += cost(row, result.row_to_col[row]);
  return result;
}

}  // namespace phdslam::assignment
