#include "src/assignment/shortest_augmenting_path.h"

#include <limits>

namespace phdslam::assignment {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Predecessor marker of a column reached through the shared slack-row node.
constexpr int kViaSlackRow = -2;

}  // namespace

void ShortestAugmentingPath::Reset(const Eigen::MatrixXd& cost) {
  ClearState(static_cast<int>(cost.rows()), static_cast<int>(cost.cols()));
  cost_.resize(static_cast<std::size_t>(rows_) * cols_);
  for (int i = 0; i < rows_; ++i) {
    for (int j = 0; j < cols_; ++j) this->cost(i, j) = cost(i, j);
  }
}

void ShortestAugmentingPath::Reset(int rows, int cols) {
  ClearState(rows, cols);
  cost_.assign(static_cast<std::size_t>(rows_) * cols_, kInf);
}

void ShortestAugmentingPath::ClearState(int rows, int cols) {
  rows_ = rows;
  cols_ = cols;
  col_for_row.assign(rows_, -1);
  row_for_col.assign(cols_, -1);
  row_dual.assign(rows_, 0.0);
  col_dual.assign(cols_, 0.0);
  free_column_dual = 0.0;
  col_active.assign(cols_, 1);
  distance_.resize(cols_);
  predecessor_.resize(cols_);
  unscanned_cols_.reserve(cols_);
  scanned_rows_.reserve(rows_);
  scanned_cols_.reserve(cols_);
}

// Dijkstra over reduced costs from `start_row`. Without a target the sink is the first unassigned
// column reached (all of them share one dual, so reduced path lengths compare true cost changes).
// With a target, the unassigned columns lead to the shared slack-row node instead, whose reduced
// cost to column j is free_column_dual - col_dual[j] >= 0, and the only sink is the target.
bool ShortestAugmentingPath::Augment(int start_row, int target_col) {
  unscanned_cols_.clear();
  for (int j = 0; j < cols_; ++j) {
    if (!col_active[j]) continue;
    unscanned_cols_.push_back(j);
    distance_[j] = kInf;
    predecessor_[j] = -1;
  }
  scanned_rows_.clear();
  scanned_cols_.clear();

  const auto is_sink = [&](int j) { return target_col < 0 ? row_for_col[j] < 0 : j == target_col; };

  int row = start_row;
  double path_length = 0.0;
  bool reached_slack = false;
  double slack_distance = 0.0;
  int slack_entry_col = -1;
  int sink = -1;
  while (true) {
    if (row >= 0) {
      scanned_rows_.push_back(row);
      const double* row_cost = &cost_[static_cast<std::size_t>(row) * cols_];
      const double base = path_length - row_dual[row];
      for (const int j : unscanned_cols_) {
        const double d = base + row_cost[j] - col_dual[j];
        if (d < distance_[j]) {
          distance_[j] = d;
          predecessor_[j] = row;
        }
      }
    }
    double lowest = kInf;
    int lowest_index = -1;
    for (int index = 0; index < static_cast<int>(unscanned_cols_.size()); ++index) {
      const int j = unscanned_cols_[index];
      const double d = distance_[j];
      if (d < lowest || (d == lowest && d < kInf && is_sink(j))) {
        lowest = d;
        lowest_index = index;
      }
    }
    if (lowest_index < 0) return false;
    path_length = lowest;
    const int col = unscanned_cols_[lowest_index];
    unscanned_cols_[lowest_index] = unscanned_cols_.back();
    unscanned_cols_.pop_back();
    if (is_sink(col)) {
      sink = col;
      break;
    }
    if (row_for_col[col] >= 0) {
      scanned_cols_.push_back(col);
      row = row_for_col[col];
      continue;
    }
    // An unassigned column in target mode: enter the slack-row node. Every other unassigned column
    // is reached at this same distance through it, so they are all settled at once.
    reached_slack = true;
    slack_distance = path_length;
    slack_entry_col = col;
    row = -1;
    std::size_t kept = 0;
    for (const int j : unscanned_cols_) {
      if (row_for_col[j] < 0 && j != target_col) continue;
      const double d = slack_distance + free_column_dual - col_dual[j];
      if (d < distance_[j]) {
        distance_[j] = d;
        predecessor_[j] = kViaSlackRow;
      }
      unscanned_cols_[kept++] = j;
    }
    unscanned_cols_.resize(kept);
  }

  // Dual update: keeps reduced costs non-negative and makes the path tight.
  row_dual[start_row] += path_length;
  for (std::size_t k = 1; k < scanned_rows_.size(); ++k) {
    const int i = scanned_rows_[k];
    row_dual[i] += path_length - distance_[col_for_row[i]];
  }
  for (const int j : scanned_cols_) col_dual[j] -= path_length - distance_[j];
  if (reached_slack) {
    free_column_dual -= path_length - slack_distance;
    for (int j = 0; j < cols_; ++j) {
      if (col_active[j] && row_for_col[j] < 0 && j != target_col) col_dual[j] = free_column_dual;
    }
  }

  // Augment along the predecessor chain from the sink back to the start row.
  int col = sink;
  while (true) {
    const int i = predecessor_[col];
    if (i == kViaSlackRow) {
      // A slack row takes this column (it becomes unassigned) and gives up its entry column.
      row_for_col[col] = -1;
      col_dual[col] = free_column_dual;
      col = slack_entry_col;
      continue;
    }
    row_for_col[col] = i;
    const int previous = col_for_row[i];
    col_for_row[i] = col;
    if (i == start_row) break;
    col = previous;
  }
  return true;
}

}  // namespace phdslam::assignment
