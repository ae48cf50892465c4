#include "src/assignment/linear_assignment.h"

#include <cmath>
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

std::optional<Assignment> SolveLinearAssignment(const Eigen::MatrixXd& cost) {
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
