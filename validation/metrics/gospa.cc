#include "validation/metrics/gospa.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "src/assignment/linear_assignment.h"

namespace phdslam::validation {
namespace {

void ValidateInput(const std::vector<Vec2>& truth, const std::vector<Vec2>& estimate, double c,
                   double p, const char* caller) {
  if (!(c > 0.0) || !std::isfinite(c)) {
    throw std::invalid_argument(std::string(caller) + ": cut-off c = " + std::to_string(c) +
                                "; expected a finite c > 0");
  }
  if (!(p >= 1.0) || !std::isfinite(p)) {
    throw std::invalid_argument(std::string(caller) + ": order p = " + std::to_string(p) +
                                "; expected a finite p >= 1");
  }
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (!truth[i].allFinite()) {
      throw std::invalid_argument(std::string(caller) + ": truth point " + std::to_string(i) +
                                  " is not finite");
    }
  }
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    if (!estimate[i].allFinite()) {
      throw std::invalid_argument(std::string(caller) + ": estimate point " + std::to_string(i) +
                                  " is not finite");
    }
  }
}

// Optimal assignment of the smaller set into the larger on min(d, c)^p. Returns, for each truth
// index, the estimate index it is paired with (every point of the smaller set is paired).
std::vector<int> CutOffAssignment(const std::vector<Vec2>& truth, const std::vector<Vec2>& estimate,
                                  double c, double p) {
  const bool truth_rows = truth.size() <= estimate.size();
  const std::vector<Vec2>& rows = truth_rows ? truth : estimate;
  const std::vector<Vec2>& cols = truth_rows ? estimate : truth;
  Eigen::MatrixXd cost(rows.size(), cols.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = 0; j < cols.size(); ++j) {
      cost(i, j) = std::pow(std::min((rows[i] - cols[j]).norm(), c), p);
    }
  }
  const auto solution = assignment::SolveLinearAssignment(cost);
  // Every entry is finite, so a solution always exists.
  std::vector<int> estimate_for_truth(truth.size(), -1);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const int j = solution->row_to_col[i];
    if (truth_rows) {
      estimate_for_truth[i] = j;
    } else {
      estimate_for_truth[j] = static_cast<int>(i);
    }
  }
  return estimate_for_truth;
}

}  // namespace

GospaResult Gospa(const std::vector<Vec2>& truth, const std::vector<Vec2>& estimate, double c,
                  double p) {
  ValidateInput(truth, estimate, c, p, "Gospa");
  GospaResult result;
  const std::vector<int> estimate_for_truth = CutOffAssignment(truth, estimate, c, p);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const int j = estimate_for_truth[i];
    if (j < 0) continue;
    const double d = (truth[i] - estimate[j]).norm();
    if (d >= c) continue;
    result.localisation += std::pow(d, p);
    result.pairs.emplace_back(static_cast<int>(i), j);
  }
  const int n_pairs = static_cast<int>(result.pairs.size());
  result.n_missed = static_cast<int>(truth.size()) - n_pairs;
  result.n_false = static_cast<int>(estimate.size()) - n_pairs;
  const double half_cp = 0.5 * std::pow(c, p);
  result.missed = half_cp * result.n_missed;
  result.false_ = half_cp * result.n_false;
  result.gospa = std::pow(result.localisation + result.missed + result.false_, 1.0 / p);
  return result;
}

OspaResult Ospa(const std::vector<Vec2>& truth, const std::vector<Vec2>& estimate, double c,
                double p) {
  ValidateInput(truth, estimate, c, p, "Ospa");
  OspaResult result;
  const std::size_t n = std::max(truth.size(), estimate.size());
  const std::size_t m = std::min(truth.size(), estimate.size());
  if (n == 0) return result;
  const std::vector<int> estimate_for_truth = CutOffAssignment(truth, estimate, c, p);
  double localisation = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const int j = estimate_for_truth[i];
    if (j >= 0) localisation += std::pow(std::min((truth[i] - estimate[j]).norm(), c), p);
  }
  const double cardinality = std::pow(c, p) * static_cast<double>(n - m);
  const double inv_n = 1.0 / static_cast<double>(n);
  result.ospa = std::pow((localisation + cardinality) * inv_n, 1.0 / p);
  result.localisation = std::pow(localisation * inv_n, 1.0 / p);
  result.cardinality = std::pow(cardinality * inv_n, 1.0 / p);
  return result;
}

}  // namespace phdslam::validation
