// Per-step pose errors and the paper's pooled RMSE (docs/algorithms/metrics.md section 1).
#pragma once

#include <cstddef>
#include <vector>

#include "src/core/types.h"

namespace phdslam::validation {

struct PoseErrors {
  std::vector<double> position_m;   ///< ||p_k - p_hat_k|| (m)
  std::vector<double> heading_rad;  ///< |theta_k - theta_hat_k| (rad), NOT wrapped
};

/// Errors at every step. The heading error is the absolute unwrapped difference (the headings are
/// never wrapped, so a filter that loses a full turn scores 2 pi). Throws std::invalid_argument
/// when the sizes differ or a pose is not finite.
PoseErrors ComputePoseErrors(const std::vector<Pose>& truth, const std::vector<Pose>& estimate);

struct PooledRmse {
  double rmse = 0.0;       ///< sqrt(mean e^2) over every added error; NaN when none was added
  double error_std = 0.0;  ///< sample std (n - 1) of the errors; 0 for one error, NaN for none
  std::size_t count = 0;
};

/// Pools errors over steps and runs: sqrt(mean e^2) and the standard deviation of the errors
/// themselves (the paper's "+-1 std"). Add every run's per-step errors, or Merge per-run
/// accumulators; the result does not depend on the order.
class RmseAccumulator {
 public:
  /// Throws std::invalid_argument when `error` is not finite.
  void Add(double error);
  void Add(const std::vector<double>& errors);
  /// Adds the finite entries and skips NaN ones (steps without a reference, e.g. GPS gaps);
  /// returns how many were added. Throws std::invalid_argument on +-inf.
  std::size_t AddSkippingNaN(const std::vector<double>& errors);
  void Merge(const RmseAccumulator& other);
  PooledRmse Result() const;

 private:
  std::size_t count_ = 0;
  double sum_squares_ = 0.0;
  double mean_ = 0.0;  // running mean of the errors (Welford)
  double sum_sq_deviation_ = 0.0;
};

}  // namespace phdslam::validation
