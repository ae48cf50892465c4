#include "validation/runner/evaluation/wilcoxon.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace phdslam::validation {
namespace {

// P(W <= w) for the signed-rank statistic of n untied ranks 1..n under the null hypothesis:
// the number of subsets of {1..n} with sum <= w, divided by 2^n.
double ExactCdf(std::size_t n, double w) {
  const std::size_t max_sum = n * (n + 1) / 2;
  std::vector<double> counts(max_sum + 1, 0.0);
  counts[0] = 1.0;
  for (std::size_t rank = 1; rank <= n; ++rank) {
    for (std::size_t s = max_sum; s >= rank; --s) counts[s] += counts[s - rank];
  }
  double below = 0.0;
  for (std::size_t s = 0; s <= max_sum && static_cast<double>(s) <= w; ++s) below += counts[s];
  return below / std::ldexp(1.0, static_cast<int>(n));
}

}  // namespace

double Median(std::vector<double> values) {
  if (values.empty()) throw std::invalid_argument("Median: no values");
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  const double lower =
      *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lower + upper);
}

WilcoxonResult WilcoxonSignedRank(const std::vector<double>& differences) {
  WilcoxonResult result;
  result.n = differences.size();
  std::vector<std::pair<double, bool>> magnitudes;  // (|d|, d > 0)
  for (double d : differences) {
    if (!std::isfinite(d)) {
      throw std::invalid_argument("WilcoxonSignedRank: a difference is not finite");
    }
    if (d != 0.0) magnitudes.emplace_back(std::abs(d), d > 0.0);
  }
  const std::size_t n = magnitudes.size();
  result.n_nonzero = n;
  if (n == 0) return result;
  std::sort(magnitudes.begin(), magnitudes.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });

  // Average ranks over runs of equal |d|; tie term sum (t^3 - t).
  double tie_term = 0.0;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j + 1 < n && magnitudes[j + 1].first == magnitudes[i].first) ++j;
    const double rank = 0.5 * static_cast<double>(i + 1 + j + 1);
    const double t = static_cast<double>(j - i + 1);
    tie_term += t * t * t - t;
    for (std::size_t k = i; k <= j; ++k) {
      (magnitudes[k].second ? result.w_plus : result.w_minus) += rank;
    }
    i = j + 1;
  }
  result.statistic = std::min(result.w_plus, result.w_minus);

  const bool has_zeros = n < differences.size();
  const double count = static_cast<double>(n);
  if (n <= kWilcoxonExactLimit && !has_zeros && tie_term == 0.0) {
    result.method = WilcoxonMethod::kExact;
    result.p_value = std::min(1.0, 2.0 * ExactCdf(n, result.statistic));
    return result;
  }
  result.method = WilcoxonMethod::kNormal;
  const double mean = count * (count + 1.0) / 4.0;
  const double variance = count * (count + 1.0) * (2.0 * count + 1.0) / 24.0 - tie_term / 48.0;
  const double offset = result.statistic - mean;
  const double correction = offset > 0.0 ? 0.5 : (offset < 0.0 ? -0.5 : 0.0);
  if (variance <= 0.0) {
    result.p_value = 1.0;
    return result;
  }
  result.z = (offset - correction) / std::sqrt(variance);
  result.p_value = std::min(1.0, std::erfc(std::abs(*result.z) / std::sqrt(2.0)));
  return result;
}

}  // namespace phdslam::validation
