// Paired comparisons of estimators run on the same Monte Carlo seeds: for each metric and each
// pair of (estimator, particles) groups of a runs.csv, the Wilcoxon signed-rank test over their
// common seeds, written to comparison.csv (columns in validation/README.md).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "validation/runner/evaluation/wilcoxon.h"
#include "validation/runner/io/results_io.h"

namespace phdslam::validation {

struct PairedComparison {
  std::string metric;
  std::string estimator_a;
  int particles_a = 1;
  std::string estimator_b;
  int particles_b = 1;
  double median_a = 0.0;  ///< over the common seeds
  double median_b = 0.0;
  double median_difference = 0.0;  ///< median over the common seeds of a - b
  WilcoxonResult test;             ///< of the differences a - b; test.n = common seeds
};

/// Metrics compared when none are named.
inline const std::vector<std::string>& DefaultComparisonMetrics() {
  static const std::vector<std::string> metrics = {"gospa_m", "pos_rmse_m"};
  return metrics;
}

/// Compares every pair of groups (a before b in the order estimator, particles) on every metric,
/// over the seeds where both groups have a value (empty cells are missing values); pairs without
/// such a seed give no row. Rows are ordered by metric (as given), then a, then b. Throws
/// std::invalid_argument naming `source` for a metric that is not a column, and
/// std::runtime_error for a missing identity column or a cell that is not a number.
std::vector<PairedComparison> ComparePairs(const CsvTable& runs,
                                           const std::vector<std::string>& metrics,
                                           const std::string& source);

/// The comparison.csv text: header
/// metric,estimator_a,particles_a,estimator_b,particles_b,n,n_nonzero,median_a,median_b,
/// median_difference,w_plus,w_minus,statistic,z,p_value,method and one row per comparison.
std::string ComparisonCsv(const std::vector<PairedComparison>& comparisons);

/// Reads <folder>/runs.csv, compares and writes <folder>/comparison.csv atomically.
std::vector<PairedComparison> WriteComparison(const std::filesystem::path& folder,
                                              const std::vector<std::string>& metrics);

}  // namespace phdslam::validation
