#include "src/glmb/gibbs_sampler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>

#include "src/core/log_sum_exp.h"
#include "src/glmb/hash_slots.h"

namespace phdslam::glmb {

double LogEta(const EtaRow& row, int gamma) {
  if (gamma == -1) return row.log_death;
  if (gamma == 0) return row.log_miss;
  for (const auto& [j, v] : row.detections) {
    if (j == gamma - 1) return v;
  }
  return kNegInf;
}

double LogAssociationWeight(EtaRows rows, const Association& gamma) {
  // The measurements taken so far: on the stack for the usual scan, on the heap beyond it.
  constexpr int kOnStack = 256;
  std::array<char, kOnStack> taken_here{};
  std::vector<char> taken_heap;
  double total = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const int g = gamma[i];
    if (g > 0) {
      char* taken = taken_here.data();
      if (g > kOnStack) {
        if (static_cast<int>(taken_heap.size()) < g) taken_heap.resize(g, 0);
        taken = taken_heap.data();
      }
      if (taken[g - 1] != 0) return kNegInf;
      taken[g - 1] = 1;
    }
    total += LogEta(rows[i], g);
  }
  return total;
}

namespace {

/// The better of death and miss for a row that takes no measurement; ties go to "missed".
int PrivateValue(const EtaRow& row) { return row.log_miss >= row.log_death ? 0 : -1; }

/// A row's own best value and its log eta (-inf when the row allows no value).
struct OwnBest {
  int value = 0;
  double log_eta = kNegInf;
};

/// The row's own best value: the first of equal measurements, "missed" over "dead" at a tie.
OwnBest OwnBestOf(const EtaRow& row) {
  OwnBest best{PrivateValue(row), std::max(row.log_miss, row.log_death)};
  for (const auto& [j, v] : row.detections) {
    if (v > best.log_eta) best = OwnBest{j + 1, v};
  }
  return best;
}

/// Every row at its own best value, into gamma; false when two rows want one measurement (or a
/// row has no allowed value). When it exists it is the optimum: each factor is at its maximum.
bool RowWiseBest(EtaRows rows, int measurements, Association& gamma, std::vector<char>& taken) {
  gamma.resize(rows.size());
  taken.assign(static_cast<std::size_t>(measurements), 0);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const OwnBest best = OwnBestOf(rows[i]);
    const int g = best.value;
    if (best.log_eta == kNegInf) return false;
    if (g > 0) {
      if (taken[g - 1] != 0) return false;
      taken[g - 1] = 1;
    }
    gamma[i] = g;
  }
  return true;
}

/// The root of measurement j's set in `parent` (path halving).
int FindSet(std::vector<int>& parent, int j) {
  while (parent[static_cast<std::size_t>(j)] != j) {
    int& up = parent[static_cast<std::size_t>(j)];
    up = parent[static_cast<std::size_t>(up)];
    j = up;
  }
  return j;
}

/// Joins the sets of measurements a and b, the smaller root becoming the root.
void JoinSets(std::vector<int>& parent, int a, int b) {
  a = FindSet(parent, a);
  b = FindSet(parent, b);
  if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
}

/// The cost -log eta of an allowed value; a log eta of +inf is not a weight.
double CostOfLogEta(double log_eta) {
  if (log_eta == std::numeric_limits<double>::infinity()) {
    throw std::invalid_argument("OptimalAssociation: an eta row holds log eta = +inf");
  }
  return -log_eta;
}

/// Sets the contested rows into groups that compete for no common measurement: two measurements
/// are in one set when a row gates both, and a row belongs to the set of its measurements.
/// Fills scratch.contested, .grouped and .group_begin, and `out` for the other rows; false when
/// one of these has no allowed value.
bool GroupRows(EtaRows rows, int measurements, Association& out, AssociationScratch& s) {
  s.set_parent.resize(static_cast<std::size_t>(measurements));
  for (int j = 0; j < measurements; ++j) s.set_parent[static_cast<std::size_t>(j)] = j;
  s.contested.clear();
  for (int i = 0; i < static_cast<int>(rows.size()); ++i) {
    const EtaRow& row = rows[static_cast<std::size_t>(i)];
    int first = -1;
    for (const auto& [j, v] : row.detections) {
      if (!(v > kNegInf)) continue;
      if (first < 0) first = j;
      JoinSets(s.set_parent, first, j);
    }
    if (first >= 0) {
      s.contested.push_back(first);  // the row's first allowed measurement, for now
      s.contested.push_back(i);
      continue;
    }
    // Only the private column is left to this row, and no other row can take it.
    if (!(std::max(row.log_death, row.log_miss) > kNegInf)) return false;
    out[static_cast<std::size_t>(i)] = PrivateValue(row);
  }
  // A counting sort of the rows by their set's root, stable, so each group stays ascending.
  s.group_begin.assign(static_cast<std::size_t>(measurements) + 1, 0);
  for (std::size_t k = 0; k < s.contested.size(); k += 2) {
    s.contested[k] = FindSet(s.set_parent, s.contested[k]);
    ++s.group_begin[static_cast<std::size_t>(s.contested[k]) + 1];
  }
  for (int j = 0; j < measurements; ++j) {
    s.group_begin[static_cast<std::size_t>(j) + 1] += s.group_begin[static_cast<std::size_t>(j)];
  }
  s.grouped.resize(s.contested.size() / 2);
  s.column_of.assign(s.group_begin.begin(), s.group_begin.end() - 1);  // fill positions
  for (std::size_t k = 0; k < s.contested.size(); k += 2) {
    const auto root = static_cast<std::size_t>(s.contested[k]);
    s.grouped[static_cast<std::size_t>(s.column_of[root]++)] = s.contested[k + 1];
  }
  return true;
}

/// The optimal values of `group` (rows that share measurements only among themselves, ascending)
/// into out: each row's own best value when no two of them want one measurement, else the linear
/// assignment of the rows to [one private column each | the group's measurements, ascending],
/// solved by the path search (SolveLinearAssignmentByPaths' steps, in its order). `s.taken` and
/// `s.column_of` enter all zero and -1 on the group's measurements. False when the group has no
/// valid association.
bool SolveGroup(EtaRows rows, std::span<const int> group, Association& out, AssociationScratch& s) {
  bool collide = false;
  for (const int i : group) {
    const int g = OwnBestOf(rows[static_cast<std::size_t>(i)]).value;
    out[static_cast<std::size_t>(i)] = g;
    if (g > 0 && s.taken[static_cast<std::size_t>(g - 1)]++ != 0) collide = true;
  }
  if (!collide) return true;
  s.measurement_of.clear();
  for (const int i : group) {
    for (const auto& [j, v] : rows[static_cast<std::size_t>(i)].detections) {
      if (v > kNegInf && s.column_of[static_cast<std::size_t>(j)] < 0) {
        s.column_of[static_cast<std::size_t>(j)] = 0;
        s.measurement_of.push_back(j);
      }
    }
  }
  std::sort(s.measurement_of.begin(), s.measurement_of.end());
  const auto k = static_cast<int>(group.size());
  for (std::size_t c = 0; c < s.measurement_of.size(); ++c) {
    s.column_of[static_cast<std::size_t>(s.measurement_of[c])] = k + static_cast<int>(c);
  }
  s.solver.Reset(k, k + static_cast<int>(s.measurement_of.size()));
  for (int r = 0; r < k; ++r) {
    const EtaRow& row = rows[static_cast<std::size_t>(group[r])];
    const double best_private = std::max(row.log_death, row.log_miss);
    if (best_private > kNegInf) s.solver.cost(r, r) = CostOfLogEta(best_private);
    for (const auto& [j, v] : row.detections) {
      if (v > kNegInf) s.solver.cost(r, s.column_of[static_cast<std::size_t>(j)]) = CostOfLogEta(v);
    }
  }
  for (int r = 0; r < k; ++r) {
    if (!s.solver.AugmentToFreeColumn(r)) return false;
  }
  for (int r = 0; r < k; ++r) {
    const int c = s.solver.col_for_row[static_cast<std::size_t>(r)];
    const EtaRow& row = rows[static_cast<std::size_t>(group[r])];
    out[static_cast<std::size_t>(group[r])] =
        c >= k ? s.measurement_of[static_cast<std::size_t>(c - k)] + 1 : PrivateValue(row);
  }
  return true;
}

}  // namespace

bool OptimalAssociation(EtaRows rows, int measurements, Association& out,
                        AssociationScratch& scratch) {
  const int p = static_cast<int>(rows.size());
  if (p == 0) {
    out.clear();
    return true;
  }
  if (RowWiseBest(rows, measurements, out, scratch.taken)) return true;
  // The rows without an allowed measurement keep the better of death and miss; the others fall
  // into groups that compete for no common measurement, each solved on its own. Equal in real
  // arithmetic to one assignment of all rows to [private columns | measurements], and to it bit
  // for bit but at exact ties, since the path search of one group never reaches another's columns.
  out.resize(static_cast<std::size_t>(p));
  if (!GroupRows(rows, measurements, out, scratch)) return false;
  scratch.taken.assign(static_cast<std::size_t>(measurements), 0);
  scratch.column_of.assign(static_cast<std::size_t>(measurements), -1);
  for (int root = 0; root < measurements; ++root) {
    const int begin = scratch.group_begin[static_cast<std::size_t>(root)];
    const int end = scratch.group_begin[static_cast<std::size_t>(root) + 1];
    if (begin == end) continue;
    const std::span<const int> group(scratch.grouped.data() + begin,
                                     static_cast<std::size_t>(end - begin));
    if (!SolveGroup(rows, group, out, scratch)) return false;
  }
  return true;
}

std::optional<Association> OptimalAssociation(EtaRows rows, int measurements) {
  Association out;
  AssociationScratch scratch;
  if (!OptimalAssociation(rows, measurements, out, scratch)) return std::nullopt;
  return out;
}

SamplerRows MakeSamplerRows(EtaRows rows, int measurements) {
  SamplerRows out;
  out.begin.reserve(rows.size() + 1);
  out.total.reserve(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const EtaRow& row = rows[i];
    const auto first = static_cast<int>(out.value.size());
    out.begin.push_back(first);
    auto offer = [&](int g, double v) {
      if (v == kNegInf) return;
      out.value.push_back(g);
      out.slot.push_back(g > 0 ? g - 1 : measurements);
      out.weight.push_back(v);
    };
    offer(-1, row.log_death);
    offer(0, row.log_miss);
    for (const auto& [j, v] : row.detections) offer(j + 1, v);
    const auto last = static_cast<int>(out.value.size());
    out.widest = std::max(out.widest, last - first);
    double total = 0.0;
    if (last > first) {
      const auto top = std::max_element(out.weight.begin() + first, out.weight.end());
      const auto d = static_cast<int>(top - out.weight.begin());
      const double m = *top;
      // The largest value to the front, the others keeping their order.
      std::rotate(out.value.begin() + first, out.value.begin() + d, out.value.begin() + d + 1);
      std::rotate(out.slot.begin() + first, out.slot.begin() + d, out.slot.begin() + d + 1);
      std::rotate(out.weight.begin() + first, out.weight.begin() + d, out.weight.begin() + d + 1);
      for (int c = first; c < last; ++c) {
        out.weight[c] = std::exp(out.weight[c] - m);
        total += out.weight[c];
      }
    }
    out.total.push_back(total);
    const double leave = total > 0.0 ? (total - 1.0) / total : 0.0;
    out.leave.push_back(leave);
    out.rare.push_back(
        static_cast<char>(last > first && out.slot[first] == measurements && leave <= kRareLeave));
  }
  out.begin.push_back(static_cast<int>(out.value.size()));
  return out;
}

namespace {

/// The uniforms of one chain: SplitMix64 from a seed drawn from the filter's stream, 53 bits
/// per draw; a few times cheaper than drawing each from the stream's Mersenne Twister.
class ChainUniforms {
 public:
  explicit ChainUniforms(std::uint64_t seed) : state_(seed) {}
  /// Uniform on [0, 1).
  double Next() {
    state_ += 0x9e3779b97f4a7c15ULL;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_;
};

/// The contribution of gamma_n = g to an association's hash (a sum over rows, so that one row's
/// change updates it in O(1)).
std::uint64_t RowHash(int n, int g) {
  return MixSeed((static_cast<std::uint64_t>(n) << 32) ^ static_cast<std::uint32_t>(g + 1));
}

/// The state of one chain: the association, the owner of each measurement (row or -1; slot
/// `measurements` is never owned) and the association's hash.
struct ChainState {
  explicit ChainState(GibbsScratch& scratch)
      : gamma(scratch.gamma), owner(scratch.owner), cumulative(scratch.cumulative) {}
  Association& gamma;
  std::vector<int>& owner;
  std::uint64_t hash = 0;
  std::vector<double>& cumulative;  ///< running sums of a row's allowed weights
};

/// The table row of chain row n: index[n], or n when the chain's rows are the whole table.
int TableRow(std::span<const int> index, int n) { return index.empty() ? n : index[n]; }

/// Sets gamma[n] = pick, keeping the owners and the hash; true when it changed.
bool SetRow(int n, int pick, ChainState& state) {
  const int old = state.gamma[n];
  if (pick == old) return false;
  if (old > 0) state.owner[old - 1] = -1;
  if (pick > 0) state.owner[pick - 1] = n;
  state.gamma[n] = pick;
  state.hash += RowHash(n, pick) - RowHash(n, old);
  return true;
}

/// Whether a row's largest value is its pick for u without the running sums: the value is free (its
/// owner slot holds -1) or row n's own, and u times the row's total with every value allowed is
/// below 1 (ResampleRowAt).
bool TopIsPick(int top_owner, int n, double u, double total) {
  return (top_owner == -1 || top_owner == n) && u * total < 1.0;
}

/// Resamples gamma[n], whose values are row `row` of `rows`, from its conditional given u, the
/// uniform of this row and sweep; true when it changed. The pick is the first allowed value (in
/// the row's order) whose running sum of allowed weights exceeds u times their total. The largest
/// value comes first with weight 1, so when it is allowed and u times the row's total with every
/// value allowed is below 1, it is the pick without the sums: the allowed total is not larger (the
/// same sum with terms left out, rounding being monotone).
bool ResampleRowAt(double u, const SamplerRows& rows, int row, int n, ChainState& state) {
  const int first = rows.begin[row];
  const int count = rows.begin[row + 1] - first;
  if (count == 0) return false;  // unreachable from a valid state: the current value is allowed
  const int* value = rows.value.data() + first;
  const int* slot = rows.slot.data() + first;
  const double* weight = rows.weight.data() + first;
  const int* owner = state.owner.data();
  if (TopIsPick(owner[slot[0]], n, u, rows.total[row])) return SetRow(n, value[0], state);
  double* cumulative = state.cumulative.data();
  double total = 0.0;
  int last_allowed = -1;
  for (int c = 0; c < count; ++c) {
    const int o = owner[slot[c]];
    const bool allowed = o == -1 || o == n;
    total += allowed ? weight[c] : 0.0;  // + 0.0 leaves a sum >= 0 as it is
    last_allowed = allowed ? c : last_allowed;
    cumulative[c] = total;
  }
  if (!(total > 0.0)) return false;  // unreachable from a valid state: the current value is allowed
  const double target = u * total;
  // The running sums do not decrease, so the first one above target comes after the sums that
  // are not; a value that is not allowed repeats its predecessor's sum, which target already
  // reached (target >= 0), so that first sum is an allowed value's. None above target (u * total
  // rounded up to total): the last allowed value.
  int below = 0;
  for (int c = 0; c < count; ++c) below += cumulative[c] <= target ? 1 : 0;
  const int pick_c = below < count ? below : last_allowed;
  return SetRow(n, value[pick_c], state);
}

/// A geometric number of failures before the first success of chance p, log_q = log(1 - p) < 0.
std::int64_t GeometricGap(ChainUniforms& uniforms, double log_q) {
  const double v = 1.0 - uniforms.Next();  // (0, 1]
  const double g = std::floor(std::log(v) / log_q);
  return g < 4.0e18 ? static_cast<std::int64_t>(g) : std::numeric_limits<std::int64_t>::max();
}

/// The rare rows' sweeps away from their largest value (SamplerRows::rare): the cells (sweep,
/// rare row) where u lies above 1 / total form a Bernoulli process, drawn as candidates with
/// geometric gaps at the chain's largest chance `top_leave` and each kept with chance
/// leave / top_leave. Between them a rare row takes its largest value, which is allowed whatever
/// the other rows hold, without a draw.
class RareRowEvents {
 public:
  /// `rare` lists the chain's rare rows (positions n) of `table` rows index (or n when empty).
  RareRowEvents(std::span<const int> rare, const SamplerRows& table, std::span<const int> index)
      : rare_(rare), table_(table), index_(index) {
    for (int n : rare) top_leave_ = std::max(top_leave_, Leave(n));
    log_stay_ = std::log1p(-top_leave_);
  }

  /// Calls on_leave(n) for each rare row whose u lies above 1 / total in sweep s (from 1), in
  /// the order of the draws; called once per sweep, in order.
  template <class OnLeave>
  void Sweep(std::int64_t s, ChainUniforms& uniforms, OnLeave&& on_leave) {
    if (rare_.empty() || !(top_leave_ > 0.0)) return;
    const auto k = static_cast<std::int64_t>(rare_.size());
    if (next_ < 0) next_ = GeometricGap(uniforms, log_stay_);  // the first candidate cell
    const std::int64_t end = s * k;                            // cells of sweeps 1..s: [0, end)
    while (next_ < end) {
      const auto r = static_cast<std::size_t>(next_ % k);
      if (uniforms.Next() * top_leave_ < Leave(rare_[r])) on_leave(rare_[r]);
      const std::int64_t gap = GeometricGap(uniforms, log_stay_);
      next_ = gap >= std::numeric_limits<std::int64_t>::max() - next_
                  ? std::numeric_limits<std::int64_t>::max()
                  : next_ + 1 + gap;
    }
  }

 private:
  [[nodiscard]] double Leave(int n) const {
    return table_.leave[static_cast<std::size_t>(TableRow(index_, n))];
  }

  std::span<const int> rare_;
  const SamplerRows& table_;
  std::span<const int> index_;
  double top_leave_ = 0.0;
  double log_stay_ = 0.0;
  std::int64_t next_ = -1;  ///< the next candidate cell, (s - 1) * rare rows + rare index
};

/// A list of ints in storage laid out in advance for its largest size.
class IntList {
 public:
  IntList() = default;
  explicit IntList(int* data) : data_(data) {}
  void push_back(int v) { data_[size_++] = v; }
  void clear() { size_ = 0; }
  [[nodiscard]] std::size_t size() const { return size_; }
  int operator[](std::size_t i) const { return data_[i]; }
  [[nodiscard]] int* begin() const { return data_; }
  [[nodiscard]] int* end() const { return data_ + size_; }
  [[nodiscard]] std::span<const int> view() const { return {data_, size_}; }

 private:
  int* data_ = nullptr;
  std::size_t size_ = 0;
};

/// Chain row n, of table row `row`, as a dense row: its largest value and owner slot, and the
/// row's total (+inf for a row without values, whose every visit then takes ResampleRowAt).
DenseChainRow DenseRowOf(const SamplerRows& table, int row, int n, int measurements) {
  const int first = table.begin[row];
  if (table.begin[row + 1] == first) {
    return {n, row, measurements, 0, std::numeric_limits<double>::infinity()};
  }
  return {n, row, table.slot[first], table.value[first], table.total[row]};
}

/// The chain's rows by how they are resampled, in storage reused over its sweeps.
struct ChainRows {
  ChainRows(int n_rows, std::vector<int>& storage, std::vector<DenseChainRow>& dense_storage)
      : dense(dense_storage),
        rare(Reserve(storage, n_rows)),
        away(storage.data() + n_rows),
        due(storage.data() + 2 * static_cast<std::ptrdiff_t>(n_rows)) {
    dense.clear();
  }
  static int* Reserve(std::vector<int>& storage, int n_rows) {
    storage.resize(4 * static_cast<std::size_t>(n_rows));
    return storage.data();
  }
  std::vector<DenseChainRow>& dense;  ///< rows resampled every sweep with their own uniform
  IntList rare;                       ///< positions of rare rows
  IntList away;                       ///< rare rows not at their largest value after the last sweep
  IntList due;  ///< this sweep's rare rows to visit: 2 n + (1 when it leaves); at most 2 per row
};

/// Visits the rows of sweep s in order: the dense ones from their conditionals, the due rare
/// ones (leaving: from their conditional given u above 1 / total; away: back to their largest
/// value); true when the association changed.
bool RunSweep(std::int64_t s, const SamplerRows& table, std::span<const int> index, ChainRows& rows,
              RareRowEvents& events, ChainState& state, ChainUniforms& uniforms) {
  auto top_of = [&](int n) { return table.value[table.begin[TableRow(index, n)]]; };
  rows.due.clear();
  for (int n : rows.away) rows.due.push_back(2 * n);
  events.Sweep(s, uniforms, [&](int n) { rows.due.push_back(2 * n + 1); });
  if (rows.due.size() > 1) std::sort(rows.due.begin(), rows.due.end());
  rows.away.clear();
  bool changed = false;
  std::size_t d = 0;
  const int n_rows = static_cast<int>(state.gamma.size());
  for (std::size_t r = 0; r <= rows.dense.size(); ++r) {
    const int until = r < rows.dense.size() ? rows.dense[r].n : n_rows;
    for (; d < rows.due.size() && rows.due[d] / 2 < until; ++d) {
      const int n = rows.due[d] / 2;
      // An away row that also leaves appears twice (2 n, 2 n + 1): the second visit decides.
      if (d + 1 < rows.due.size() && rows.due[d + 1] / 2 == n) continue;
      const int row = TableRow(index, n);
      if (rows.due[d] % 2 == 1) {  // u above 1 / total: uniform on [1 / total, 1)
        const double floor_u = 1.0 / table.total[row];
        const double u = floor_u + (1.0 - floor_u) * uniforms.Next();
        changed |= ResampleRowAt(u, table, row, n, state);
      } else {
        changed |= SetRow(n, top_of(n), state);
      }
      if (state.gamma[n] != top_of(n)) rows.away.push_back(n);
    }
    if (r < rows.dense.size()) {
      // ResampleRowAt's shortcut from the chain's copy of the row's look-ups, then the row itself.
      const DenseChainRow& dense = rows.dense[r];
      const double u = uniforms.Next();
      changed |=
          TopIsPick(state.owner[static_cast<std::size_t>(dense.top_slot)], dense.n, u, dense.total)
              ? SetRow(dense.n, dense.top_value, state)
              : ResampleRowAt(u, table, dense.row, dense.n, state);
    }
  }
  return changed;
}

/// Runs the chain from `start` for samples - 1 sweeps, calling visit(gamma, hash, changed) on
/// every sample; changed is false when the sweep left the association as it was. Row n of the
/// chain is row index[n] of `table` (row n when index is empty).
template <class Visit>
void RunChain(const SamplerRows& table, std::span<const int> index, int measurements,
              const Association& start, int samples, RandomStream& rng, GibbsScratch& scratch,
              Visit&& visit) {
  ChainState state(scratch);
  state.gamma.assign(start.begin(), start.end());
  for (std::size_t i = 0; i < start.size(); ++i) {
    state.hash += RowHash(static_cast<int>(i), start[i]);
  }
  visit(state.gamma, state.hash, true);
  if (samples <= 1) return;  // the start only: no sweep, no draw
  state.owner.assign(static_cast<std::size_t>(measurements) + 1, -1);
  for (std::size_t i = 0; i < start.size(); ++i) {
    if (start[i] > 0) state.owner[start[i] - 1] = static_cast<int>(i);
  }
  ChainUniforms uniforms(rng.NextU64());
  state.cumulative.resize(static_cast<std::size_t>(table.widest));
  const int n_rows = static_cast<int>(start.size());
  ChainRows rows(n_rows, scratch.rows, scratch.dense);
  for (int n = 0; n < n_rows; ++n) {
    const int row = TableRow(index, n);
    if (table.rare[row] == 0) {
      rows.dense.push_back(DenseRowOf(table, row, n, measurements));
      continue;
    }
    rows.rare.push_back(n);
    if (start[n] != table.value[table.begin[row]]) rows.away.push_back(n);
  }
  RareRowEvents events(rows.rare.view(), table, index);
  for (int s = 1; s < samples; ++s) {
    const bool changed = RunSweep(s, table, index, rows, events, state, uniforms);
    visit(state.gamma, state.hash, changed);
  }
}

/// A set of associations of one length, stored flat, found by their hashes (HashSlots).
class AssociationSet {
 public:
  /// An empty set in the scratch's buffers.
  AssociationSet(std::size_t length, GibbsScratch& scratch)
      : length_(length), store_(scratch.store), hashes_(scratch.hashes), slots_(scratch.table) {
    store_.clear();
    hashes_.clear();
  }

  /// Adds gamma (whose hash is `hash`) unless present.
  void Insert(const Association& gamma, std::uint64_t hash) {
    const int found = slots_.Find(hash, [&](int k) {
      return hashes_[k] == hash && std::equal(gamma.begin(), gamma.end(), Row(k));
    });
    if (found >= 0) return;
    const auto k = static_cast<int>(hashes_.size());
    hashes_.push_back(hash);
    store_.insert(store_.end(), gamma.begin(), gamma.end());
    slots_.Insert(k, [&](int e) { return hashes_[e]; });
  }

  /// The number of members.
  [[nodiscard]] std::size_t size() const { return hashes_.size(); }

  /// The members in lexicographic order, one after the other into `flat`; `order` is scratch.
  void SortedInto(std::vector<int>& order, std::vector<int>& flat) const {
    order.resize(hashes_.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return std::lexicographical_compare(Row(a), Row(a) + length_, Row(b), Row(b) + length_);
    });
    flat.clear();
    flat.reserve(order.size() * length_);
    for (int k : order) flat.insert(flat.end(), Row(k), Row(k) + length_);
  }

 private:
  [[nodiscard]] const int* Row(int k) const {
    return store_.data() + static_cast<std::size_t>(k) * length_;
  }

  std::size_t length_;
  std::vector<int>& store_;
  std::vector<std::uint64_t>& hashes_;
  HashSlots slots_;
};

}  // namespace

std::vector<Association> GibbsSample(EtaRows rows, int measurements, const Association& start,
                                     int samples, RandomStream& rng) {
  std::vector<Association> out;
  out.reserve(std::max(1, samples));
  const SamplerRows table = MakeSamplerRows(rows, measurements);
  GibbsScratch scratch;
  RunChain(
      table, {}, measurements, start, samples, rng, scratch,
      [&](const Association& g, std::uint64_t /*hash*/, bool /*changed*/) { out.push_back(g); });
  return out;
}

std::size_t DistinctGibbsSamples(const SamplerRows& table, std::span<const int> index,
                                 int measurements, const Association& start, int samples,
                                 RandomStream& rng, GibbsScratch& scratch, std::vector<int>& flat) {
  AssociationSet seen(start.size(), scratch);
  RunChain(table, index, measurements, start, samples, rng, scratch,
           [&](const Association& g, std::uint64_t hash, bool changed) {
             if (changed) seen.Insert(g, hash);  // unchanged: the common case, already in
           });
  seen.SortedInto(scratch.order, flat);
  return seen.size();
}

std::vector<Association> DistinctGibbsSamples(const SamplerRows& table, std::span<const int> index,
                                              int measurements, const Association& start,
                                              int samples, RandomStream& rng,
                                              GibbsScratch& scratch) {
  std::vector<int> flat;
  const std::size_t count =
      DistinctGibbsSamples(table, index, measurements, start, samples, rng, scratch, flat);
  std::vector<Association> out;
  out.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    const auto first = flat.begin() + static_cast<std::ptrdiff_t>(k * start.size());
    out.emplace_back(first, first + static_cast<std::ptrdiff_t>(start.size()));
  }
  return out;
}

std::vector<Association> DistinctGibbsSamples(const SamplerRows& table, std::span<const int> index,
                                              int measurements, const Association& start,
                                              int samples, RandomStream& rng) {
  GibbsScratch scratch;
  return DistinctGibbsSamples(table, index, measurements, start, samples, rng, scratch);
}

std::vector<Association> DistinctGibbsSamples(EtaRows rows, int measurements,
                                              const Association& start, int samples,
                                              RandomStream& rng) {
  return DistinctGibbsSamples(MakeSamplerRows(rows, measurements), {}, measurements, start, samples,
                              rng);
}

std::vector<Association> DistinctAssociations(std::vector<Association> samples) {
  std::sort(samples.begin(), samples.end());
  samples.erase(std::unique(samples.begin(), samples.end()), samples.end());
  return samples;
}

}  // namespace phdslam::glmb
