// The single-cluster vs RB-PHD-SLAM parent weighting figure (Lee, Clark & Salvi 2012, Fig. 4):
// one predicted state, many parent poses drawn from it, one scan, and the normalised parent
// weights under both likelihoods (filters::CompareParentWeights).
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/types.h"

namespace phdslam::validation {

/// Most parent poses a comparison draws.
inline constexpr int kMaxParents = 100000;

struct ParentWeightsSettings {
  std::size_t step = 100;  ///< the scan whose update is compared (0-based step index)
  int parents = 300;       ///< parent poses drawn from the predicted pose Gaussian
  /// The draws use the predicted covariance scaled by spread^2. At 1, the parents of one step
  /// lie within a metre and see the same map; a wider spread (as a parent process accumulates
  /// over several steps) makes them differ in which map components fall in the field of view,
  /// which is where the single-cluster missed-detection term exp(-sum pD w) tells them apart.
  double spread = 1.0;
  std::uint64_t stream_seed = 0;  ///< seeds the filter run up to `step` and the pose draws
};

struct ParentWeights {
  std::size_t step = 0;
  Pose previous_pose = Pose::Zero();  ///< the best parent of step - 1: where the prediction starts
  Pose predicted_mean = Pose::Zero();
  Mat3 predicted_cov = Mat3::Zero();  ///< before the spread
  double spread = 1.0;
  std::optional<Pose> true_pose;  ///< at `step`, when the scenario has true poses
  std::size_t measurements = 0;
  std::size_t map_components = 0;          ///< components of the predicted map
  std::vector<Pose> poses;                 ///< the parents
  std::vector<double> single_cluster;      ///< normalised weights, eq. (33) with exp(-sum pD w)
  std::vector<double> rb_phd;              ///< normalised weights, RB-PHD-SLAM (46) alone
  std::vector<double> log_single_cluster;  ///< unnormalised log-likelihood increments
  std::vector<double> log_rb_phd;
  std::vector<double> missed_mass;  ///< sum pD w of the predicted map seen from each parent
};

/// Runs single-cluster PHD SLAM with one parent (the scenario's default parameters) over steps
/// 0 .. step - 1, predicts its best parent's pose over `step` into a Gaussian (the transition
/// density, reference notes 4.1), draws `parents` poses from it, and weighs them all with the
/// same predicted map and the measurements of `step`. Throws std::invalid_argument when step is
/// 0 or past the scenario, when the step has no measurements, when parents < 2, or when spread
/// is not positive and finite.
ParentWeights CompareParentWeightingAtStep(const datasets::Scenario& scenario,
                                           const ParentWeightsSettings& settings);

/// `parent,x,y,theta,sc_weight,rb_weight,sc_log_weight,rb_log_weight,missed_mass`, one row per
/// parent; the log-weights are normalised (log-sum-exp 0), so they stay finite where the weights
/// underflow.
std::string ParentWeightsCsv(const ParentWeights& w);

/// Everything but the rows: scenario facts, the predicted Gaussian, the true pose (or null),
/// and the effective sample size 1 / sum w^2 of each weighting.
nlohmann::json ParentWeightsJson(const ParentWeights& w);

}  // namespace phdslam::validation
