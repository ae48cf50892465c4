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
///
/// When every row's cheapest entry lies in a column of its own and below the row's other entries
/// by a clear margin (kRowMinimumMargin), that is the unique optimum and is returned without the
/// path search: the same assignment and cost, bit for bit, as SolveLinearAssignmentByPaths.
std::optional<Assignment> SolveLinearAssignment(const Eigen::MatrixXd& cost);

/// SolveLinearAssignment by the path search alone, whatever the row minima.
std::optional<Assignment> SolveLinearAssignmentByPaths(const Eigen::MatrixXd& cost);

/// How far, relative to the larger magnitude, a row's cheapest entry must lie below its second
/// cheapest for the row minima to be taken as the optimum: any other assignment then costs more by
/// far more than the path search's rounding (a few units in the last place per step).
inline constexpr double kRowMinimumMargin = 1e-9;

/// Throws std::invalid_argument, naming `caller`, unless rows <= cols and no entry is NaN or -inf.
void ValidateCostMatrix(const Eigen::MatrixXd& cost, const char* caller);

}  // namespace phdslam::assignment
