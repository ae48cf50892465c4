// The eta matrix of one prior hypothesis (docs/algorithms/glmb-slam.md section 4.2) and the Gibbs
// sampler of its joint prediction/update associations (docs/algorithms/glmb-slam.md section 4.3;
// Vo, Vo & Hoang 2017, Algorithm 1), started from the optimal association computed with the suite's
// assignment solver.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "src/assignment/shortest_augmenting_path.h"
#include "src/core/random.h"

namespace phdslam::glmb {

/// One row of eta in logs: -inf is a forbidden value (log 0), never a large finite cost.
struct EtaRow {
  double log_death = 0.0;  ///< gamma = -1: dies (survivor) or is not born (birth)
  double log_miss = 0.0;   ///< gamma = 0: survives (or is born) and is missed
  /// Gated measurements only, ascending: (j, log eta(j + 1)) for measurement index j (0-based).
  std::vector<std::pair<int, double>> detections;
};

/// The rows of one eta matrix: table[index[i]] (an empty index is a matrix without rows), or
/// table[i] when built from the table alone. The parents of
/// a joint problem share the rows of their common entries this way instead of copying them.
class EtaRows {
 public:
  // Implicit: a plain vector or span of rows is an eta matrix.
  EtaRows(std::span<const EtaRow> table)  // NOLINT(google-explicit-constructor)
      : table_(table) {}
  EtaRows(const std::vector<EtaRow>& table)  // NOLINT(google-explicit-constructor)
      : table_(table) {}
  EtaRows(std::span<const EtaRow> table, std::span<const int> index)
      : table_(table), index_(index), indexed_(true) {}
  [[nodiscard]] std::size_t size() const { return indexed_ ? index_.size() : table_.size(); }
  [[nodiscard]] const EtaRow& operator[](std::size_t i) const {
    return indexed_ ? table_[static_cast<std::size_t>(index_[i])] : table_[i];
  }

 private:
  std::span<const EtaRow> table_;
  std::span<const int> index_;
  bool indexed_ = false;
};

/// gamma_i in {-1, 0, 1..M}: -1 dead / not born, 0 missed, j >= 1 detected by measurement j - 1.
using Association = std::vector<int>;

/// log eta_i(gamma_i); -inf when gamma_i is forbidden for the row.
double LogEta(const EtaRow& row, int gamma);

/// sum_i log eta_i(gamma_i); -inf when any value is forbidden or two rows share a measurement.
double LogAssociationWeight(EtaRows rows, const Association& gamma);

/// The highest-weight valid association (minimum total cost -log eta): each row at its own best
/// value when no two of them want one measurement, else the better of death and miss for every row
/// without an allowed measurement and, for the rows with one, the linear assignment to [one private
/// column each: the better of death and miss | the M measurements]; nullopt when none is valid
/// (some row has no allowed value left).
std::optional<Association> OptimalAssociation(EtaRows rows, int measurements);

/// The buffers of OptimalAssociation, for a caller that solves many eta matrices.
struct AssociationScratch {
  std::vector<char> taken;
  std::vector<int> set_parent;   ///< disjoint sets of the measurements
  std::vector<int> contested;    ///< pairs (set of its first measurement, row) of the rows with one
  std::vector<int> group_begin;  ///< per set root: where its rows start in `grouped`
  std::vector<int> grouped;      ///< the contested rows by set, ascending within a set
  std::vector<int> column_of;    ///< a measurement's column in its group's problem
  std::vector<int> measurement_of;  ///< a group's measurements, ascending
  assignment::ShortestAugmentingPath solver;
};

/// The same into `out`, with the buffers of `scratch`, for a caller that reuses both; false when
/// no valid association exists.
bool OptimalAssociation(EtaRows rows, int measurements, Association& out,
                        AssociationScratch& scratch);

/// Eta rows in the sampler's form, computed once for a table of rows that many chains share:
/// each row's allowed values with their linear weights exp(log eta - row max), row r's values
/// being [begin[r], begin[r + 1]): its largest value first (weight 1, the first of ties), then the
/// others in the order -1, 0, the gated measurements.
struct SamplerRows {
  std::vector<int> begin;
  std::vector<int> value;  ///< gamma
  /// The owner slot a value needs free: j for measurement j, `measurements` (never owned) for
  /// death and miss.
  std::vector<int> slot;
  std::vector<double> weight;
  std::vector<double> total;  ///< per row: the sum of its weights in order, all values allowed
  /// Per row: true when its largest value can never be taken by another row (death or miss) and
  /// the chance 1 - 1 / total of u falling above it is at most kRareLeave. Such a row keeps its
  /// largest value except at rare sweeps, which the chain draws in advance (RunChain).
  std::vector<char> rare;
  std::vector<double> leave;  ///< per row: 1 - 1 / total (0 for a row without values)
  int widest = 0;             ///< the most values of one row
};

/// The largest chance per sweep of leaving its largest value for a row the chain skips.
inline constexpr double kRareLeave = 1.0 / 16.0;

SamplerRows MakeSamplerRows(EtaRows rows, int measurements);

/// `samples` associations (at least 1): `start` (which must be valid) followed by samples - 1
/// Gibbs sweeps, rows resampled in order from their conditionals given the other rows (a
/// measurement taken by another row is excluded), conditionals shifted by their maximum before
/// exponentiation, each row's values in the order: its largest, then the others as in the row.
/// One draw from `rng` seeds the chain (none when samples = 1); then uniforms from the chain's
/// SplitMix64 sequence: one per row and sweep for the other rows; for the rare rows (SamplerRows)
/// the sweeps at which u exceeds 1 / total are drawn as a Bernoulli process (geometric gaps at the
/// chain's largest leave, thinned to each row's), the row keeping its largest value in between.
std::vector<Association> GibbsSample(EtaRows rows, int measurements, const Association& start,
                                     int samples, RandomStream& rng);

/// The distinct associations, in lexicographic order.
std::vector<Association> DistinctAssociations(std::vector<Association> samples);

/// DistinctAssociations(GibbsSample(...)) with the same draws, without storing repeated samples.
std::vector<Association> DistinctGibbsSamples(EtaRows rows, int measurements,
                                              const Association& start, int samples,
                                              RandomStream& rng);

/// The same for the eta matrix whose row n is row index[n] of `table` (MakeSamplerRows of a
/// shared table of rows, such as JointProblem::eta).
std::vector<Association> DistinctGibbsSamples(const SamplerRows& table, std::span<const int> index,
                                              int measurements, const Association& start,
                                              int samples, RandomStream& rng);

/// A row that a chain resamples at every sweep, with the look-ups of its common case (its largest
/// value free and u times its total below 1), copied from SamplerRows once per chain.
struct DenseChainRow {
  int n = 0;           ///< the chain's row
  int row = 0;         ///< its row of the SamplerRows table
  int top_slot = 0;    ///< the owner slot of its largest value
  int top_value = 0;   ///< its largest value
  double total = 0.0;  ///< SamplerRows::total of the row
};

/// Buffers of the chains (their state, rows and set of distinct samples), which a caller running
/// many chains reuses to save their allocations; their contents between calls mean nothing.
struct GibbsScratch {
  Association gamma;
  std::vector<int> owner;
  std::vector<double> cumulative;
  std::vector<int> rows;
  std::vector<DenseChainRow> dense;
  std::vector<int> store;
  std::vector<std::uint64_t> hashes;
  std::vector<int> table;  ///< HashSlots of the distinct samples
  std::vector<int> order;
};

/// The same with the chain's buffers in `scratch`: the same samples as without it.
std::vector<Association> DistinctGibbsSamples(const SamplerRows& table, std::span<const int> index,
                                              int measurements, const Association& start,
                                              int samples, RandomStream& rng,
                                              GibbsScratch& scratch);

/// The same samples written one after the other into `flat` (start.size() values each), for a
/// caller that keeps them in its own form; returns their number (at least 1, also when
/// start.size() is 0 and `flat` stays empty).
std::size_t DistinctGibbsSamples(const SamplerRows& table, std::span<const int> index,
                                 int measurements, const Association& start, int samples,
                                 RandomStream& rng, GibbsScratch& scratch, std::vector<int>& flat);

}  // namespace phdslam::glmb
