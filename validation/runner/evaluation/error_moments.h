// Sufficient statistics (count, sum, sum of squares) of per-step errors, kept per run so that
// errors can be pooled over all steps of all runs without re-reading the steps.
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>

namespace phdslam::validation {

struct ErrorMoments {
  std::size_t count = 0;
  double sum = 0.0;
  double sum_sq = 0.0;

  /// Adds one value; NaN values are ignored (they mark "not available").
  void Add(double value) {
    if (std::isnan(value)) return;
    ++count;
    sum += value;
    sum_sq += value * value;
  }
  void Merge(const ErrorMoments& other) {
    count += other.count;
    sum += other.sum;
    sum_sq += other.sum_sq;
  }
  /// Root mean square, sqrt(sum_sq / count); nullopt when empty.
  [[nodiscard]] std::optional<double> Rms() const {
    if (count == 0) return std::nullopt;
    return std::sqrt(sum_sq / static_cast<double>(count));
  }
  [[nodiscard]] std::optional<double> Mean() const {
    if (count == 0) return std::nullopt;
    return sum / static_cast<double>(count);
  }
  /// Sample standard deviation (divisor count - 1) of the values; nullopt for fewer than two.
  [[nodiscard]] std::optional<double> Std() const {
    if (count < 2) return std::nullopt;
    const double n = static_cast<double>(count);
    const double var = (sum_sq - sum * sum / n) / (n - 1.0);
    return std::sqrt(var > 0.0 ? var : 0.0);
  }
};

}  // namespace phdslam::validation
