// The batch (whole-scenario) estimator interface of the reference estimators such as the Ceres
// smoother. Unlike an online estimator it receives a whole Scenario: the runner hands the hidden
// origin labels only to entries that declare they read the truth, and a copy without them to the
// others (see validation/runner/registry/estimator_registry.h).
#pragma once

#include <optional>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/types.h"
#include "src/filters/estimator.h"

namespace phdslam::datasets {

/// Result of a batch estimator.
struct BatchResult {
  std::vector<Pose> poses;                     ///< one per step
  std::vector<std::optional<Mat3>> pose_covs;  ///< marginal covariances where computed
  filters::MapEstimate map;
  int iterations = 0;
  /// Whether the final solve converged (an iterative solver; empty when not applicable). A run
  /// whose solve did not converge carries solver_converged = false in its metrics.
  std::optional<bool> converged;
  /// Re-localisations applied, for an estimator that re-localises during the run (the Ceres
  /// smoother's own association with re-localisation on); empty when it cannot re-localise.
  std::optional<int> relocalisations;
  /// The negative log posterior of the final trajectory, map and association under the
  /// scenario's model, in nats, up to terms shared by every solution of the same data (the Ceres
  /// smoother: reference/ceres/association_posterior.h); empty for estimators that do not score it.
  std::optional<double> neg_log_posterior;
  double solve_seconds = 0.0;
};

/// A batch estimator consumes the whole scenario at once; an implementation documents which
/// hidden parts (origin labels) a mode reads, if any.
class BatchEstimator {
 public:
  virtual ~BatchEstimator() = default;
  virtual BatchResult Solve(const Scenario& scenario) = 0;
};

}  // namespace phdslam::datasets
