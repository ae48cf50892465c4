#include "src/glmb/gibbs_sampler.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

#include "src/assignment/linear_assignment.h"
#include "src/core/log_sum_exp.h"

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
  std::vector<char> taken;
  double total = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const int g = gamma[i];
    if (g > 0) {
      if (static_cast<int>(taken.size()) < g) taken.resize(g, 0);
      if (taken[g - 1] != 0) return kNegInf;
      taken[g - 1] = 1;
    }
    total += LogEta(rows[i], g);
  }
  return total;
}

namespace {

/// Every row at its own best value; nullopt when two rows want one measurement (or a row has no
/// allowed value). When it exists it is the optimum: each factor is at its maximum.
std::optional<Association> RowWiseBest(EtaRows rows, int measurements) {
  Association gamma(rows.size());
  std::vector<char> taken(measurements, 0);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    int g = rows[i].log_miss >= rows[i].log_death ? 0 : -1;
    double best = std::max(rows[i].log_miss, rows[i].log_death);
    for (const auto& [j, v] : rows[i].detections) {
      if (v > best) {
        best = v;
        g = j + 1;
      }
    }
    if (best == kNegInf) return std::nullopt;
    if (g > 0) {
      if (taken[g - 1] != 0) return std::nullopt;
      taken[g - 1] = 1;
    }
    gamma[i] = g;
  }
  return gamma;
}

}  // namespace

std::optional<Association> OptimalAssociation(EtaRows rows, int measurements) {
  const int p = static_cast<int>(rows.size());
  if (p == 0) return Association{};
  if (std::optional<Association> fast = RowWiseBest(rows, measurements)) return fast;
  Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(p, p + measurements, assignment::kForbidden);
  for (int i = 0; i < p; ++i) {
    const double best_private = std::max(rows[i].log_death, rows[i].log_miss);
    if (best_private > kNegInf) cost(i, i) = -best_private;
    for (const auto& [j, v] : rows[i].detections) {
      if (v > kNegInf) cost(i, p + j) = -v;
    }
  }
  const std::optional<assignment::Assignment> a = assignment::SolveLinearAssignment(cost);
  if (!a) return std::nullopt;
  Association gamma(p);
  for (int i = 0; i < p; ++i) {
    const int c = a->row_to_col[i];
    if (c >= p) {
      gamma[i] = c - p + 1;
    } else {
      // Ties between death and miss go to "missed".
      gamma[i] = rows[i].log_miss >= rows[i].log_death ? 0 : -1;
    }
  }
  return gamma;
}

namespace {

/// A row's allowed values with their linear weights exp(log eta - row max), computed once per
/// chain so that a sweep needs no exponentials.
struct LinearRow {
  std::vector<int> choices;     ///< gamma values, -1 and 0 first, then the gated measurements
  std::vector<double> weights;  ///< aligned with choices
};

LinearRow Linearise(const EtaRow& row) {
  LinearRow out;
  auto offer = [&](int g, double v) {
    if (v == kNegInf) return;
    out.choices.push_back(g);
    out.weights.push_back(v);
  };
  offer(-1, row.log_death);
  offer(0, row.log_miss);
  for (const auto& [j, v] : row.detections) offer(j + 1, v);
  if (out.weights.empty()) return out;
  const double m = *std::max_element(out.weights.begin(), out.weights.end());
  for (double& w : out.weights) w = std::exp(w - m);
  return out;
}

/// Resamples gamma[n] from its conditional; owner[j] is the row holding measurement j or -1.
/// One uniform is drawn whatever the row.
void ResampleRow(const LinearRow& row, int n, Association& gamma, std::vector<int>& owner,
                 RandomStream& rng) {
  const double u = rng.Uniform();
  auto allowed = [&](std::size_t c) {
    const int g = row.choices[c];
    return g <= 0 || owner[g - 1] == -1 || owner[g - 1] == n;
  };
  double total = 0.0;
  for (std::size_t c = 0; c < row.choices.size(); ++c) {
    if (allowed(c)) total += row.weights[c];
  }
  if (!(total > 0.0)) return;  // unreachable from a valid state: the current value is allowed
  const double target = u * total;
  double acc = 0.0;
  int pick = gamma[n];
  for (std::size_t c = 0; c < row.choices.size(); ++c) {
    if (!allowed(c)) continue;
    pick = row.choices[c];
    acc += row.weights[c];
    if (target < acc) break;
  }
  const int old = gamma[n];
  if (old > 0) owner[old - 1] = -1;
  gamma[n] = pick;
  if (pick > 0) owner[pick - 1] = n;
}

/// Runs the chain from `start` for samples - 1 sweeps, calling visit(gamma) on every sample.
template <class Visit>
void RunChain(EtaRows rows, int measurements, const Association& start, int samples,
              RandomStream& rng, Visit&& visit) {
  visit(start);
  if (samples <= 1) return;  // the start only: no sweep, no draw
  Association gamma = start;
  std::vector<int> owner(measurements, -1);
  for (std::size_t i = 0; i < gamma.size(); ++i) {
    if (gamma[i] > 0) owner[gamma[i] - 1] = static_cast<int>(i);
  }
  std::vector<LinearRow> linear;
  linear.reserve(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) linear.push_back(Linearise(rows[i]));
  const int n_rows = static_cast<int>(rows.size());
  for (int s = 1; s < samples; ++s) {
    for (int n = 0; n < n_rows; ++n) ResampleRow(linear[n], n, gamma, owner, rng);
    visit(gamma);
  }
}

struct AssociationHash {
  std::size_t operator()(const Association& a) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (int v : a) h = MixSeed(h ^ static_cast<std::uint64_t>(static_cast<std::int64_t>(v)));
    return static_cast<std::size_t>(h);
  }
};

}  // namespace

std::vector<Association> GibbsSample(EtaRows rows, int measurements, const Association& start,
                                     int samples, RandomStream& rng) {
  std::vector<Association> out;
  out.reserve(std::max(1, samples));
  RunChain(rows, measurements, start, samples, rng,
           [&](const Association& g) { out.push_back(g); });
  return out;
}

std::vector<Association> DistinctGibbsSamples(EtaRows rows, int measurements,
                                              const Association& start, int samples,
                                              RandomStream& rng) {
  std::unordered_set<Association, AssociationHash> seen;
  std::vector<Association> out;
  const Association* last = nullptr;
  RunChain(rows, measurements, start, samples, rng, [&](const Association& g) {
    if (last != nullptr && *last == g) return;  // the common case: the chain stayed
    const auto [it, inserted] = seen.insert(g);
    last = &*it;
    if (inserted) out.push_back(g);
  });
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Association> DistinctAssociations(std::vector<Association> samples) {
  std::sort(samples.begin(), samples.end());
  samples.erase(std::unique(samples.begin(), samples.end()), samples.end());
  return samples;
}

}  // namespace phdslam::glmb
