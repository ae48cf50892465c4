#include "src/assignment/murty.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory_resource>
#include <queue>
#include <stdexcept>
#include <string>

#include "src/assignment/shortest_augmenting_path.h"

namespace phdslam::assignment {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Stack bytes of one ranking: enough for the gated blocks of PHD-SLAM's association matrices.
constexpr std::size_t kArenaBytes = std::size_t{32} * 1024;

// Murty's partitioning. Every solved subproblem ("node") keeps its assignment, its duals, the rows
// it forces and one forbidden pair; its full set of forbidden pairs is that pair plus those of the
// node it was partitioned from. When a node is output, its unforced rows are put in partition
// order and one child per row is queued, unsolved, under a dual lower bound of its cost; a child
// is solved (one augmenting path from its parent's state) only when it reaches the queue's front.
class MurtyRanker {
 public:
  explicit MurtyRanker(const Eigen::MatrixXd& cost)
      : arena_(arena_bytes_.data(), arena_bytes_.size()),
        cost_matrix_(cost),
        solver_(&arena_),
        nodes_(&arena_),
        node_col_for_row_(&arena_),
        node_row_forced_(&arena_),
        node_row_dual_(&arena_),
        node_col_dual_(&arena_),
        orders_(&arena_),
        queue_(LaterFirst{}, std::pmr::vector<QueueEntry>(&arena_)),
        saved_entries_(&arena_),
        removed_cols_(&arena_),
        row_slack_(&arena_),
        row_slack_col_(&arena_) {
    rows_ = static_cast<int>(cost.rows());
    cols_ = static_cast<int>(cost.cols());
  }
  MurtyRanker(const MurtyRanker&) = delete;
  MurtyRanker& operator=(const MurtyRanker&) = delete;

  std::vector<Assignment> Run(int k, double max_cost_gap);

 private:
  struct Node {
    double cost = 0.0;
    double free_column_dual = 0.0;
    int parent = -1;
    int forbidden_row = -1;
    int forbidden_col = -1;
    int order_offset = 0;  // partition order, filled when the node is expanded
    int order_size = 0;
  };
  // A queued subproblem: either a solved node (node >= 0, key = its cost) or the unsolved child
  // `child` of node `parent` (key = a lower bound of its cost).
  struct QueueEntry {
    double key = 0.0;
    int node = -1;
    int parent = -1;
    int child = -1;
  };
  struct LaterFirst {
    bool operator()(const QueueEntry& a, const QueueEntry& b) const {
      if (a.key != b.key) return a.key > b.key;
      return (a.node < 0) && (b.node >= 0);  // on ties, output solved nodes first
    }
  };
  struct SavedEntry {
    int row;
    int col;
    double value;
  };

  int* NodeAssignment(int node) {
    return &node_col_for_row_[static_cast<std::size_t>(node) * rows_];
  }
  char* NodeForced(int node) { return &node_row_forced_[static_cast<std::size_t>(node) * rows_]; }
  double* NodeRowDual(int node) { return &node_row_dual_[static_cast<std::size_t>(node) * rows_]; }
  double* NodeColDual(int node) { return &node_col_dual_[static_cast<std::size_t>(node) * cols_]; }

  int StoreSolverState(int parent, int forbidden_row, int forbidden_col);
  void LoadSolverState(int node);
  void Forbid(int row, int col);
  void ForbidNodePairs(int node);
  void RestoreForbidden();
  double ReducedSlack(int row, const std::pmr::vector<char>& removed_cols, int* argmin) const;
  void Expand(int node);
  int SolveChild(int parent, int child);

  // Every list below lives in this arena: the ranker's stack frame first, the heap beyond it.
  std::array<std::byte, kArenaBytes> arena_bytes_;  // uninitialised: the arena writes it
  std::pmr::monotonic_buffer_resource arena_;
  const Eigen::MatrixXd& cost_matrix_;
  int rows_ = 0;
  int cols_ = 0;
  ShortestAugmentingPath solver_;
  std::pmr::vector<Node> nodes_;
  std::pmr::vector<int> node_col_for_row_;
  std::pmr::vector<char> node_row_forced_;
  std::pmr::vector<double> node_row_dual_;
  std::pmr::vector<double> node_col_dual_;
  std::pmr::vector<int> orders_;
  std::priority_queue<QueueEntry, std::pmr::vector<QueueEntry>, LaterFirst> queue_;
  // Workspace.
  std::pmr::vector<SavedEntry> saved_entries_;
  std::pmr::vector<char> removed_cols_;
  std::pmr::vector<double> row_slack_;
  std::pmr::vector<int> row_slack_col_;
};

int MurtyRanker::StoreSolverState(int parent, int forbidden_row, int forbidden_col) {
  const int node = static_cast<int>(nodes_.size());
  Node n;
  n.parent = parent;
  n.forbidden_row = forbidden_row;
  n.forbidden_col = forbidden_col;
  n.free_column_dual = solver_.free_column_dual;
  for (int i = 0; i < rows_; ++i) n.cost += solver_.cost(i, solver_.col_for_row[i]);
  nodes_.push_back(n);
  node_col_for_row_.insert(node_col_for_row_.end(), solver_.col_for_row.begin(),
                           solver_.col_for_row.end());
  node_row_dual_.insert(node_row_dual_.end(), solver_.row_dual.begin(), solver_.row_dual.end());
  node_col_dual_.insert(node_col_dual_.end(), solver_.col_dual.begin(), solver_.col_dual.end());
  node_row_forced_.resize(node_row_forced_.size() + rows_, 0);
  return node;
}

void MurtyRanker::LoadSolverState(int node) {
  const int* assignment = NodeAssignment(node);
  const char* forced = NodeForced(node);
  std::copy(assignment, assignment + rows_, solver_.col_for_row.begin());
  std::copy(NodeRowDual(node), NodeRowDual(node) + rows_, solver_.row_dual.begin());
  std::copy(NodeColDual(node), NodeColDual(node) + cols_, solver_.col_dual.begin());
  solver_.free_column_dual = nodes_[node].free_column_dual;
  std::fill(solver_.row_for_col.begin(), solver_.row_for_col.end(), -1);
  std::fill(solver_.col_active.begin(), solver_.col_active.end(), 1);
  for (int i = 0; i < rows_; ++i) {
    solver_.row_for_col[assignment[i]] = i;
    if (forced[i]) solver_.col_active[assignment[i]] = 0;
  }
}

void MurtyRanker::Forbid(int row, int col) {
  saved_entries_.push_back({row, col, solver_.cost(row, col)});
  solver_.cost(row, col) = kInf;
}

void MurtyRanker::ForbidNodePairs(int node) {
  for (int n = node; n >= 0; n = nodes_[n].parent) {
    if (nodes_[n].forbidden_row >= 0) Forbid(nodes_[n].forbidden_row, nodes_[n].forbidden_col);
  }
}

void MurtyRanker::RestoreForbidden() {
  for (auto it = saved_entries_.rbegin(); it != saved_entries_.rend(); ++it) {
    solver_.cost(it->row, it->col) = it->value;
  }
  saved_entries_.clear();
}

// Smallest reduced cost of `row` to an active column other than its own and not removed: by dual
// feasibility, forbidding the row's current pair raises the optimal cost by at least this much.
double MurtyRanker::ReducedSlack(int row, const std::pmr::vector<char>& removed_cols,
                                 int* argmin) const {
  const int own = solver_.col_for_row[row];
  const double row_dual = solver_.row_dual[row];
  double best = kInf;
  *argmin = -1;
  for (int j = 0; j < cols_; ++j) {
    if (j == own || !solver_.col_active[j] || removed_cols[j]) continue;
    const double slack = solver_.cost(row, j) - row_dual - solver_.col_dual[j];
    if (slack < best) {
      best = slack;
      *argmin = j;
    }
  }
  return best;
}

void MurtyRanker::Expand(int node) {
  LoadSolverState(node);
  ForbidNodePairs(node);
  const char* forced = NodeForced(node);
  std::fill(removed_cols_.begin(), removed_cols_.end(), 0);

  // Partition order (Miller, Stone & Cox): rows whose exclusion costs most come first, so the
  // children that are likely to be output next are the ones with the most forced rows, which are
  // the smallest subproblems to partition further.
  Node& n = nodes_[node];
  n.order_offset = static_cast<int>(orders_.size());
  for (int i = 0; i < rows_; ++i) {
    if (forced[i]) continue;
    row_slack_[i] = ReducedSlack(i, removed_cols_, &row_slack_col_[i]);
    orders_.push_back(i);
  }
  n.order_size = static_cast<int>(orders_.size()) - n.order_offset;
  const auto order_begin = orders_.begin() + n.order_offset;
  std::sort(order_begin, orders_.end(), [&](int a, int b) {
    if (row_slack_[a] != row_slack_[b]) return row_slack_[a] > row_slack_[b];
    return a < b;
  });

  const double parent_cost = n.cost;
  for (int child = 0; child < n.order_size; ++child) {
    const int row = orders_[n.order_offset + child];
    double slack = row_slack_[row];
    if (row_slack_col_[row] >= 0 && removed_cols_[row_slack_col_[row]]) {
      slack = ReducedSlack(row, removed_cols_, &row_slack_col_[row]);
    }
    if (slack < kInf) {
      queue_.push({std::max(parent_cost, parent_cost + slack), -1, node, child});
    }
    removed_cols_[solver_.col_for_row[row]] = 1;  // later children force this row
  }
  RestoreForbidden();
}

int MurtyRanker::SolveChild(int parent, int child) {
  LoadSolverState(parent);
  ForbidNodePairs(parent);
  const Node& p = nodes_[parent];
  const int* order = &orders_[p.order_offset];
  const int row = order[child];
  const int released_col = solver_.col_for_row[row];
  Forbid(row, released_col);
  for (int q = 0; q < child; ++q) solver_.col_active[solver_.col_for_row[order[q]]] = 0;
  solver_.col_for_row[row] = -1;
  solver_.row_for_col[released_col] = -1;
  const bool feasible = solver_.AugmentToReleasedColumn(row, released_col);
  RestoreForbidden();
  if (!feasible) return -1;
  const int node = StoreSolverState(parent, row, released_col);
  char* forced = NodeForced(node);
  const char* parent_forced = NodeForced(parent);
  std::copy(parent_forced, parent_forced + rows_, forced);
  for (int q = 0; q < child; ++q) forced[orders_[nodes_[parent].order_offset + q]] = 1;
  return node;
}

std::vector<Assignment> MurtyRanker::Run(int k, double max_cost_gap) {
  std::vector<Assignment> results;
  if (k == 0) return results;
  if (rows_ == 0) {
    results.push_back(Assignment{});
    return results;
  }
  solver_.Reset(cost_matrix_);
  for (int row = 0; row < rows_; ++row) {
    if (!solver_.AugmentToFreeColumn(row)) return results;
  }
  removed_cols_.assign(cols_, 0);
  row_slack_.assign(rows_, 0.0);
  row_slack_col_.assign(rows_, -1);
  // Room for the nodes of a short ranking (PHD-SLAM keeps a few hypotheses); more grow the lists.
  const std::size_t expected_nodes = static_cast<std::size_t>(std::min(k, 16)) * 2;
  nodes_.reserve(expected_nodes);
  node_col_for_row_.reserve(expected_nodes * rows_);
  node_row_forced_.reserve(expected_nodes * rows_);
  node_row_dual_.reserve(expected_nodes * rows_);
  node_col_dual_.reserve(expected_nodes * cols_);
  orders_.reserve(expected_nodes * rows_);
  results.reserve(static_cast<std::size_t>(std::min(k, 64)));

  const int root = StoreSolverState(-1, -1, -1);
  queue_.push({nodes_[root].cost, root, -1, -1});
  const double best_cost = nodes_[root].cost;
  while (!queue_.empty() && static_cast<int>(results.size()) < k) {
    const QueueEntry top = queue_.top();
    queue_.pop();
    if (!results.empty() && top.key - best_cost > max_cost_gap) break;
    if (top.node < 0) {
      const int node = SolveChild(top.parent, top.child);
      if (node >= 0) {
        queue_.push({std::max(nodes_[node].cost, nodes_[top.parent].cost), node, -1, -1});
      }
      continue;
    }
    const int* assignment = NodeAssignment(top.node);
    results.push_back(
        Assignment{std::vector<int>(assignment, assignment + rows_), nodes_[top.node].cost});
    if (static_cast<int>(results.size()) < k) Expand(top.node);
  }
  return results;
}

}  // namespace

std::vector<Assignment> MurtyKBest(const Eigen::MatrixXd& cost, int k) {
  return MurtyKBest(cost, k, kInf);
}

std::vector<Assignment> MurtyKBest(const Eigen::MatrixXd& cost, int k, double max_cost_gap) {
  ValidateCostMatrix(cost, "MurtyKBest");
  if (k < 0)
    throw std::invalid_argument("MurtyKBest: k is " + std::to_string(k) + "; expected k >= 0");
  if (std::isnan(max_cost_gap)) {
    throw std::invalid_argument("MurtyKBest: max_cost_gap is NaN; expected a number or +inf");
  }
  MurtyRanker ranker(cost);
  return ranker.Run(k, max_cost_gap);
}

}  // namespace phdslam::assignment
