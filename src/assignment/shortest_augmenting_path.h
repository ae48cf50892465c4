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
#include <memory_resource>
#include <vector>

namespace phdslam::assignment {

class ShortestAugmentingPath {
 public:
  /// Every list of the state and the workspace is allocated from `resource`.
  explicit ShortestAugmentingPath(
      std::pmr::memory_resource* resource = std::pmr::get_default_resource())
      : col_for_row(resource),
        row_for_col(resource),
        row_dual(resource),
        col_dual(resource),
        col_active(resource),
        cost_(resource),
        distance_(resource),
        predecessor_(resource),
        unscanned_cols_(resource),
        scanned_rows_(resource),
        scanned_cols_(resource) {}

  /// Copies `cost` (row-major), clears the assignment and the duals, activates everything.
  void Reset(const Eigen::MatrixXd& cost);

  /// The same for a rows x cols problem with every pair forbidden (+inf), for a caller that then
  /// sets the allowed entries with cost(i, j); reuses the buffers of earlier problems.
  void Reset(int rows, int cols);

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
  std::pmr::vector<int> col_for_row;  // -1 when unassigned
  std::pmr::vector<int> row_for_col;  // -1 when unassigned
  std::pmr::vector<double> row_dual;
  std::pmr::vector<double> col_dual;
  double free_column_dual = 0.0;
  std::pmr::vector<char> col_active;  // inactive columns are ignored by the path search

 private:
  bool Augment(int start_row, int target_col);
  /// Sizes everything but the cost matrix to rows x cols; no assignment, zero duals, all active.
  void ClearState(int rows, int cols);

  int rows_ = 0;
  int cols_ = 0;
  std::pmr::vector<double> cost_;
  // Path-search workspace, sized once per Reset.
  std::pmr::vector<double> distance_;
  std::pmr::vector<int> predecessor_;
  std::pmr::vector<int> unscanned_cols_;
  std::pmr::vector<int> scanned_rows_;
  std::pmr::vector<int> scanned_cols_;
};

}  // namespace phdslam::assignment
