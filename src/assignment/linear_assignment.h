// Exact minimum-cost rectangular linear assignment (every row to a distinct column).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <vector>

namespace phdslam::assignment {

/// Cost of a forbidden row-column pair.
inline constexpr double kForbidden = std::numeric_limits<double>::infinity();

/// One assignment: row_to_col[i] is the column of row i; cost is the sum of the chosen entries,
/// added in row order.
struct Assignment {
  std::vector<int> row_to_col;
  double cost = 0.0;
};

/// Minimum-cost assignment of every row to a distinct column (rows <= cols); +inf entries are
/// forbidden. Returns nullopt when no feasible assignment exists. Exact: shortest augmenting paths
/// with dual variables (Jonker-Volgenant style). A matrix with no rows gives the empty assignment.
/// Throws std::invalid_argument when rows > cols or an entry is NaN or -inf.
std::optional<Assignment> SolveLinearAssignment(const Eigen::MatrixXd& cost);

/// Throws std::invalid_argument, naming `caller`, unless rows <= cols and no entry is NaN or -inf.
void ValidateCostMatrix(const Eigen::MatrixXd& cost, const char* caller);

}  // namespace phdslam::assignment
