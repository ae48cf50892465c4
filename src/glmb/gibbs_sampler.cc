#include "src/glmb/gibbs_sampler.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

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

double LogAssociationWeight(std::span<const EtaRow> rows, const Association& gamma) {
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

std::optional<Association> OptimalAssociation(std::span<const EtaRow> rows, int measurements) {
  const int p = static_cast<int>(rows.size());
  if (p == 0) return Association{};
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

/// Resamples gamma[n] from its conditional; owner[j] is the row holding measurement j or -1.
void ResampleRow(std::span<const EtaRow> rows, int n, Association& gamma, std::vector<int>& owner,
                 std::vector<double>& values, std::vector<int>& choices, RandomStream& rng) {
  const EtaRow& row = rows[n];
  values.clear();
  choices.clear();
  auto offer = [&](int g, double v) {
    if (v == kNegInf) return;
    values.push_back(v);
    choices.push_back(g);
  };
  offer(-1, row.log_death);
  offer(0, row.log_miss);
  for (const auto& [j, v] : row.detections) {
    if (owner[j] == -1 || owner[j] == n) offer(j + 1, v);
  }
  const double u = rng.Uniform();
  if (values.empty()) return;  // unreachable from a valid state: the current value is allowed
  const double m = *std::max_element(values.begin(), values.end());
  double total = 0.0;
  for (double& v : values) {
    v = std::exp(v - m);
    total += v;
  }
  const double target = u * total;
  double acc = 0.0;
  std::size_t pick = values.size() - 1;
  for (std::size_t c = 0; c < values.size(); ++c) {
    acc += values[c];
    if (target < acc) {
      pick = c;
      break;
    }
  }
  const int old = gamma[n];
  if (old > 0) owner[old - 1] = -1;
  gamma[n] = choices[pick];
  if (gamma[n] > 0) owner[gamma[n] - 1] = n;
}

}  // namespace

std::vector<Association> GibbsSample(std::span<const EtaRow> rows, int measurements,
                                     const Association& start, int samples, RandomStream& rng) {
  std::vector<Association> out;
  out.reserve(std::max(1, samples));
  out.push_back(start);
  Association gamma = start;
  std::vector<int> owner(measurements, -1);
  for (std::size_t i = 0; i < gamma.size(); ++i) {
    if (gamma[i] > 0) owner[gamma[i] - 1] = static_cast<int>(i);
  }
  std::vector<double> values;
  std::vector<int> choices;
  const int n_rows = static_cast<int>(rows.size());
  for (int s = 1; s < samples; ++s) {
    for (int n = 0; n < n_rows; ++n) ResampleRow(rows, n, gamma, owner, values, choices, rng);
    out.push_back(gamma);
  }
  return out;
}

std::vector<Association> DistinctAssociations(std::vector<Association> samples) {
  std::sort(samples.begin(), samples.end());
  samples.erase(std::unique(samples.begin(), samples.end()), samples.end());
  return samples;
}

}  // namespace phdslam::glmb
