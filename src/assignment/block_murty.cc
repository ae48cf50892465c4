#include "src/assignment/block_murty.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory_resource>
#include <numeric>
#include <stdexcept>

#include "src/assignment/murty.h"

namespace phdslam::assignment {
namespace {

/// Stack bytes for the block structure of one cost matrix.
constexpr std::size_t kArenaBytes = std::size_t{4} * 1024;

int Find(std::pmr::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

std::vector<Assignment> BlockMurtyKBest(const Eigen::MatrixXd& cost, int k, double max_cost_gap) {
  const int rows = static_cast<int>(cost.rows());
  const int cols = static_cast<int>(cost.cols());
  if (k <= 0 || rows == 0) return MurtyKBest(cost, k, max_cost_gap);
  if (rows > cols) throw std::invalid_argument("BlockMurtyKBest: more rows than columns");
  if (std::isnan(max_cost_gap)) throw std::invalid_argument("BlockMurtyKBest: NaN cost gap");

  // The finite columns of every row (one flat list), and rows that share one joined in a block.
  std::array<std::byte, kArenaBytes> arena_bytes;  // uninitialised: the arena writes it
  std::pmr::monotonic_buffer_resource arena(arena_bytes.data(), arena_bytes.size());
  std::pmr::vector<int> row_start(rows + 1, 0, &arena);
  std::pmr::vector<int> finite_cols(&arena);
  finite_cols.reserve(static_cast<std::size_t>(rows) * 4);
  std::pmr::vector<int> parent(rows, &arena);
  std::iota(parent.begin(), parent.end(), 0);
  std::pmr::vector<int> first_row_of_col(cols, -1, &arena);
  for (int r = 0; r < rows; ++r) {
    row_start[r] = static_cast<int>(finite_cols.size());
    for (int c = 0; c < cols; ++c) {
      const double v = cost(r, c);
      if (v == std::numeric_limits<double>::infinity()) continue;  // forbidden: most entries
      if (std::isnan(v) || v == -std::numeric_limits<double>::infinity()) {
        throw std::invalid_argument("BlockMurtyKBest: cost entry is NaN or -inf");
      }
      finite_cols.push_back(c);
      if (first_row_of_col[c] < 0) {
        first_row_of_col[c] = r;
      } else {
        parent[Find(parent, r)] = Find(parent, first_row_of_col[c]);
      }
    }
  }
  row_start[rows] = static_cast<int>(finite_cols.size());
  std::pmr::vector<int> block_size(rows, 0, &arena);
  for (int r = 0; r < rows; ++r) ++block_size[Find(parent, r)];
  if (block_size[Find(parent, 0)] == rows) return MurtyKBest(cost, k, max_cost_gap);

  // Blocks with one option within the gap are fixed into `base`; the others are ranked and
  // combined by index, partial lists cut to k entries within the gap.
  Assignment base{std::vector<int>(rows, -1), 0.0};
  struct MultiBlock {
    std::vector<int> rows;
    std::vector<int> cols;
    std::vector<Assignment> ranked;
  };
  std::vector<MultiBlock> multi;
  std::pmr::vector<char> done(rows, 0, &arena);
  for (int r0 = 0; r0 < rows; ++r0) {
    if (done[r0]) continue;
    const int root = Find(parent, r0);
    if (block_size[root] == 1) {
      // A single row: its k best assignments are its finite entries in cost order.
      done[r0] = 1;
      const int b0 = row_start[r0];
      const int b1 = row_start[r0 + 1];
      if (b0 == b1) return {};  // no feasible assignment
      int best = finite_cols[b0];
      for (int b = b0 + 1; b < b1; ++b) {
        if (cost(r0, finite_cols[b]) < cost(r0, best)) best = finite_cols[b];
      }
      const double best_cost = cost(r0, best);
      int within = 0;
      for (int b = b0; b < b1; ++b) {
        if (cost(r0, finite_cols[b]) - best_cost <= max_cost_gap) ++within;
      }
      if (within == 1 || k == 1) {
        base.row_to_col[r0] = best;
        base.cost += best_cost;
        continue;
      }
      MultiBlock mb;
      mb.rows = {r0};
      for (int b = b0; b < b1; ++b) {
        const int c = finite_cols[b];
        if (cost(r0, c) - best_cost > max_cost_gap) continue;
        mb.cols.push_back(c);
        mb.ranked.push_back({{static_cast<int>(mb.cols.size()) - 1}, cost(r0, c)});
      }
      std::stable_sort(mb.ranked.begin(), mb.ranked.end(),
                       [](const Assignment& x, const Assignment& y) { return x.cost < y.cost; });
      if (static_cast<int>(mb.ranked.size()) > k) mb.ranked.resize(k);
      multi.push_back(std::move(mb));
      continue;
    }
    // A block of several rows: rank it with Murty on its own columns.
    MultiBlock mb;
    for (int r = r0; r < rows; ++r) {
      if (!done[r] && Find(parent, r) == root) {
        mb.rows.push_back(r);
        done[r] = 1;
      }
    }
    for (int c = 0; c < cols; ++c) {
      if (first_row_of_col[c] >= 0 && Find(parent, first_row_of_col[c]) == root) {
        mb.cols.push_back(c);
      }
    }
    const int nr = static_cast<int>(mb.rows.size());
    const int nc = static_cast<int>(mb.cols.size());
    if (nc < nr) return {};
    Eigen::MatrixXd sub(nr, nc);
    for (int a = 0; a < nr; ++a) {
      for (int b = 0; b < nc; ++b) sub(a, b) = cost(mb.rows[a], mb.cols[b]);
    }
    mb.ranked = MurtyKBest(sub, k, max_cost_gap);
    if (mb.ranked.empty()) return {};
    if (mb.ranked.size() == 1) {
      base.cost += mb.ranked[0].cost;
      for (int i = 0; i < nr; ++i)
        base.row_to_col[mb.rows[i]] = mb.cols[mb.ranked[0].row_to_col[i]];
    } else {
      multi.push_back(std::move(mb));
    }
  }
  if (multi.empty()) return {base};

  // Partial combinations: cost and the chosen entry of each multi block so far.
  struct Partial {
    double cost;
    std::vector<int> choice;
  };
  std::vector<Partial> combined = {{base.cost, {}}};
  std::vector<Partial> next;
  for (const MultiBlock& mb : multi) {
    const double best = combined.front().cost + mb.ranked.front().cost;
    next.clear();
    for (const Partial& partial : combined) {
      for (std::size_t e = 0; e < mb.ranked.size(); ++e) {
        const double total = partial.cost + mb.ranked[e].cost;
        if (total - best > max_cost_gap) break;  // `ranked` is sorted
        Partial p{total, partial.choice};
        p.choice.push_back(static_cast<int>(e));
        next.push_back(std::move(p));
      }
    }
    std::stable_sort(next.begin(), next.end(),
                     [](const Partial& x, const Partial& y) { return x.cost < y.cost; });
    if (static_cast<int>(next.size()) > k) next.resize(k);
    combined.swap(next);
  }
  std::vector<Assignment> out;
  out.reserve(combined.size());
  for (const Partial& p : combined) {
    Assignment a{base.row_to_col, p.cost};
    for (std::size_t b = 0; b < multi.size(); ++b) {
      const MultiBlock& mb = multi[b];
      const Assignment& local = mb.ranked[p.choice[b]];
      for (std::size_t i = 0; i < mb.rows.size(); ++i) {
        a.row_to_col[mb.rows[i]] = mb.cols[local.row_to_col[i]];
      }
    }
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace phdslam::assignment
