// What one Monte Carlo run of one estimator produces, before any metric is computed.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "src/core/types.h"
#include "src/filters/estimator.h"
#include "src/filters/solve_counter.h"

namespace phdslam::validation {

struct RunRecord {
  std::string estimator;
  int particles = 1;
  std::uint64_t seed = 0;         ///< Monte Carlo (scenario) seed
  std::uint64_t stream_seed = 0;  ///< seed of the estimator's random stream
  /// A posterior Cramer-Rao bound (EstimatorEntry::bound): poses are the truth and pose_covs the
  /// bound, which the evaluation reports where other runs report errors.
  bool bound = false;
  /// False for a deterministic estimator (one that takes only --particles 1: the smoothers,
  /// EKF-SLAM, dead reckoning): it has no particle weights, so no ESS and no resampling rate.
  bool particle_weights = true;

  /// One entry per filter step k: the step's time stamp (its last one) and the estimate there.
  std::vector<double> step_times;
  std::vector<Pose> poses;
  /// Per step, where the estimator carries one (may be empty: no covariances at all).
  std::vector<std::optional<Mat3>> pose_covs;
  /// Per step, the Rao-Blackwellised pose mean and covariance (StepOutput::pose_mean_rb,
  /// pose_cov_rb); empty for estimators without them.
  std::vector<std::optional<Pose>> pose_means_rb;
  std::vector<std::optional<Mat3>> pose_covs_rb;
  /// Per step for online estimators; empty for batch estimators.
  std::vector<filters::StepDiagnostics> diagnostics;
  /// Per step for online estimators: StepOutput::association (per measurement the associated
  /// landmark mean or NaN; empty when the estimator reported no association). Empty for batch
  /// estimators.
  std::vector<std::vector<Landmark>> associations;
  /// Wall time of each Step call (ms, steady_clock); empty for batch estimators.
  std::vector<double> step_ms;
  /// Batch estimators: the solver's iterations (BatchResult::iterations); nullopt for online ones.
  std::optional<int> solver_iterations;
  /// Batch estimators: whether the final solve converged (BatchResult::converged).
  std::optional<bool> solver_converged;
  /// Batch estimators that re-localise: the re-localisations applied
  /// (BatchResult::relocalisations); nullopt for every other estimator.
  std::optional<int> relocalisations;
  /// Batch estimators that score their solution (the Ceres smoother): its negative log
  /// posterior (BatchResult::neg_log_posterior); nullopt for every other estimator.
  std::optional<double> neg_log_posterior;
  /// Online estimators that solve (filters::SolveCounter): their solves after the last step.
  std::optional<filters::SolveCounts> solves;
  /// Wall time of the whole estimation (ms): the sum of step_ms, or the batch solve.
  double total_ms = 0.0;
  /// The map estimate after the last step.
  filters::MapEstimate final_map;
  /// Per step, when particles were recorded and the estimator exposes them: (pose, log-weight)
  /// of every particle after the step (OnlineEstimator::ParticleStates). Otherwise empty.
  std::vector<std::vector<std::pair<Pose, double>>> particle_states;
  /// Per step, when map traces were requested (online estimators): the means of the map estimate
  /// after the step. Otherwise empty.
  std::vector<std::vector<Landmark>> step_maps;
};

}  // namespace phdslam::validation
