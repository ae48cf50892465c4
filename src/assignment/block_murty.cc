#include "src/assignment/block_murty.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "src/assignment/murty.h"

namespace phdslam::assignment {
namespace {

int Find(std::vector<int>& parent, int i) {
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

  // Rows that share a finite column belong to one block.
  std::vector<int> parent(rows);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<int> first_row_of_col(cols, -1);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (!std::isfinite(cost(r, c))) continue;
      if (first_row_of_col[c] < 0) {
        first_row_of_col[c] = r;
      } else {
        parent[Find(parent, r)] = Find(parent, first_row_of_col[c]);
      }
    }
  }
  std::vector<std::vector<int>> block_rows;
  std::vector<int> block_of_root(rows, -1);
  for (int r = 0; r < rows; ++r) {
    const int root = Find(parent, r);
    if (block_of_root[root] < 0) {
      block_of_root[root] = static_cast<int>(block_rows.size());
      block_rows.emplace_back();
    }
    block_rows[block_of_root[root]].push_back(r);
  }
  if (block_rows.size() == 1) return MurtyKBest(cost, k, max_cost_gap);

  // Each block's ranked list; blocks with one option are fixed into `base`, the others are
  // combined by index, partial lists cut to k entries within the gap.
  Assignment base{std::vector<int>(rows, -1), 0.0};
  struct MultiBlock {
    std::vector<int> rows;
    std::vector<int> cols;
    std::vector<Assignment> ranked;
  };
  std::vector<MultiBlock> multi;
  std::vector<int> bc;
  for (const std::vector<int>& br : block_rows) {
    bc.clear();
    for (int c = 0; c < cols; ++c) {
      for (int r : br) {
        if (std::isfinite(cost(r, c))) {
          bc.push_back(c);
          break;
        }
      }
    }
    const int nr = static_cast<int>(br.size());
    const int nc = static_cast<int>(bc.size());
    if (nc < nr) return {};  // this block has no feasible assignment
    std::vector<Assignment> ranked;
    if (nr == 1) {
      // A single row: its k best assignments are its finite entries in cost order.
      ranked.reserve(nc);
      for (int b = 0; b < nc; ++b) {
        Assignment a{{b}, cost(br[0], bc[b])};
        auto pos = ranked.end();
        while (pos != ranked.begin() && (pos - 1)->cost > a.cost) --pos;
        ranked.insert(pos, std::move(a));
      }
      while (!ranked.empty() && (static_cast<int>(ranked.size()) > k ||
                                 ranked.back().cost - ranked.front().cost > max_cost_gap)) {
        ranked.pop_back();
      }
    } else {
      Eigen::MatrixXd sub(nr, nc);
      for (int a = 0; a < nr; ++a) {
        for (int b = 0; b < nc; ++b) sub(a, b) = cost(br[a], bc[b]);
      }
      ranked = MurtyKBest(sub, k, max_cost_gap);
    }
    if (ranked.empty()) return {};
    if (ranked.size() == 1) {
      base.cost += ranked[0].cost;
      for (int i = 0; i < nr; ++i) base.row_to_col[br[i]] = bc[ranked[0].row_to_col[i]];
    } else {
      multi.push_back({br, bc, std::move(ranked)});
    }
  }

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
