// Shortest augmenting path machinery shared by SolveLinearAssignment and Murty's k-best ranking.
//
// The rectangular problem (rows <= cols) is treated as the square problem obtained by adding
// cols - rows identical "slack" rows of zero cost. In an optimal dual solution of that square
// problem every slack row has the same dual, so every unassigned column carries the same column
// dual (free_column_dual) and every assigned column has a dual no larger than it. The slack rows
// are never stored: they behave as one shared node reached through the cheapest unassigned column.
//
// Invariants kept between calls, for the active rows and columns:
//   * reduced costs cost(i, j) - row_dual[i] - col_dual[j] are >= 0,
//   * they are 0 on assigned pairs,
//   * unassigned columns have col_dual == free_column_dual, assigned ones col_dual <= it.
// These certify that the current partial assignment is optimal for the rows it covers, and they
// stay valid when an entry is forbidden or a row with its column is removed, which is what lets a
// Murty subproblem re-use its parent's solution and need a single augmentation.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace phdslam::assignment {

class ShortestAugmentingPath {
 public:
  /// Copies `cost` (row-major), clears the assignment and the duals, activates everything.
  void Reset(const Eigen::MatrixXd& cost);

  int rows() const { return rows_; }
  int cols() const { return cols_; }

  /// Entry (i, j) of the working cost matrix; callers may set it to +inf to forbid a pair.
  double& cost(int i, int j) { return cost_[static_cast<std::size_t>(i) * cols_ + j]; }
  double cost(int i, int j) const { return cost_[static_cast<std::size_t>(i) * cols_ + j]; }

  /// Assigns the unassigned active row `start_row` along a shortest augmenting path that ends in
  /// any unassigned active column. Returns false (state unchanged) when no such path exists.
  bool AugmentToFreeColumn(int start_row) { return Augment(start_row, -1); }

  /// Assigns the unassigned active row `start_row` when exactly one column, `target_col`, has just
  /// been released (its dual may be below the free-column dual). The resulting assignment is
  /// optimal for the active rows; the path may move an unassigned column's role to another column.
  /// Returns false (state unchanged) when no feasible assignment exists.
  bool AugmentToReleasedColumn(int start_row, int target_col) {
    return Augment(start_row, target_col);
  }

  // State, read and written directly by the callers that save and restore it.
  std::vector<int> col_for_row;  // -1 when unassigned
  std::vector<int> row_for_col;  // -1 when unassigned
  std::vector<double> row_dual;
  std::vector<double> col_dual;
  double free_column_dual = 0.0;
  std::vector<char> col_active;  // inactive columns are ignored by the path search

 private:
  bool Augment(int start_row, int target_col);

  int rows_ = 0;
  int cols_ = 0;
  std::vector<double> cost_;
  // Path-search workspace, sized once per Reset.
  std::vector<double> distance_;
  std::vector<int> predecessor_;
  std::vector<int> unscanned_cols_;
  std::vector<int> scanned_rows_;
  std::vector<int> scanned_cols_;
};

}  // namespace phdslam::assignment
