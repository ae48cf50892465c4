// The Wilcoxon signed-rank test of paired samples (two-sided), as used to compare estimators run
// on the same Monte Carlo seeds.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace phdslam::validation {

enum class WilcoxonMethod {
  kExact,   ///< exact null distribution of the statistic
  kNormal,  ///< normal approximation with tie and continuity corrections
  kNone,    ///< every difference is zero: no test
};

struct WilcoxonResult {
  std::size_t n = 0;              ///< differences given
  std::size_t n_nonzero = 0;      ///< differences used: zeros are dropped (Wilcoxon's convention)
  double w_plus = 0.0;            ///< sum of the ranks of |d| over positive differences
  double w_minus = 0.0;           ///< the same over negative differences
  double statistic = 0.0;         ///< min(w_plus, w_minus)
  std::optional<double> z;        ///< normal approximation only
  std::optional<double> p_value;  ///< two-sided; nullopt for kNone
  WilcoxonMethod method = WilcoxonMethod::kNone;
};

/// Largest number of nonzero differences for which the exact distribution is used.
inline constexpr std::size_t kWilcoxonExactLimit = 25;

/// Two-sided Wilcoxon signed-rank test of the paired differences d_i = a_i - b_i. Zero
/// differences are dropped; |d| are ranked with average ranks for ties. With at most
/// kWilcoxonExactLimit nonzero differences, no zero differences and no ties, the p-value is
/// exact: 2 P(W <= statistic), capped at 1. Otherwise z = (statistic - m - 0.5 sign(statistic -
/// m)) / s with m = n(n+1)/4, s^2 = n(n+1)(2n+1)/24 - sum_ties (t^3 - t)/48 (n nonzero
/// differences), and p = 2 (1 - Phi(|z|)). Matches scipy.stats.wilcoxon(d, correction=True)
/// with method "exact" or "approx" respectively. Throws std::invalid_argument for a NaN or
/// infinite difference.
WilcoxonResult WilcoxonSignedRank(const std::vector<double>& differences);

/// The median (mean of the two middle values for an even count); throws std::invalid_argument
/// when `values` is empty.
double Median(std::vector<double> values);

}  // namespace phdslam::validation
