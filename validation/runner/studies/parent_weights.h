// The single-cluster vs RB-PHD-SLAM parent weighting figure (Lee, Clark & Salvi 2012, Fig. 4):
// one predicted state, many parent poses drawn from it, one scan, and the normalised parent
// weights under both likelihoods (CompareParentWeights).
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/types.h"
#include "src/models/sensor_model.h"
#include "src/phd/gm_phd_map.h"
#include "src/phd/map_params.h"

namespace phdslam::validation {

/// One parent under the three weightings of CompareParentWeights.
struct ParentWeighting {
  double single_cluster = 0.0;  ///< normalised weight, single-cluster likelihood
  double rb_phd = 0.0;          ///< normalised weight, RB-PHD-SLAM weighting (46)
  /// The log-likelihood increments themselves (unnormalised); log_rb_phd - log_single_cluster is
  /// the parent's missed-detection mass sum pD w.
  double log_single_cluster = 0.0;
  double log_rb_phd = 0.0;
  /// Normalised weight and log-likelihood under Mullane et al.'s single-feature map strategy
  /// (filters/rb_phd_weighting.h), the comparator of the single-cluster paper.
  double single_feature = 0.0;
  double log_single_feature = 0.0;
};

/// For the report's weighting figure: parents with the same predicted map at the poses
/// `parent_poses` and equal prior weights, updated with one scan. Returns, per parent, its
/// weight under the single-cluster likelihood, with the missed-detection term exp(-sum pD w),
/// under the RB-PHD-SLAM weighting (46), sum_j log(lambda_c + ...) alone, and under Mullane et
/// al.'s single-feature map strategy on the same update.
/// `params` supplies the gate; its two reference_* likelihood options are overridden.
std::vector<ParentWeighting> CompareParentWeights(std::span<const Pose> parent_poses,
                                                  const phd::GmPhdMap& predicted_map,
                                                  std::span<const Measurement> measurements,
                                                  const models::SensorModel& sensor,
                                                  const phd::MapParams& params);

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
  std::vector<double> missed_mass;     ///< sum pD w of the predicted map seen from each parent
  std::vector<double> single_feature;  ///< normalised weights, single-feature RB-PHD-SLAM
  std::vector<double> log_single_feature;
};

/// Runs single-cluster PHD SLAM with one parent (the scenario's default parameters) over steps
/// 0 .. step - 1, predicts its best parent's pose over `step` into a Gaussian (the transition
/// density, docs/algorithms/models.md section 2.4), draws `parents` poses from it, and weighs them
/// all with the same predicted map and the measurements of `step`. Throws std::invalid_argument
/// when step is 0 or past the scenario, when the step has no measurements, when parents < 2, or
/// when spread is not positive and finite.
ParentWeights CompareParentWeightingAtStep(const datasets::Scenario& scenario,
                                           const ParentWeightsSettings& settings);

/// `parent,x,y,theta,sc_weight,rb_weight,sc_log_weight,rb_log_weight,missed_mass,sf_weight,
/// sf_log_weight`, one row per parent (sf: the single-feature strategy); the log-weights are
/// normalised (log-sum-exp 0), so they stay finite where the weights underflow.
std::string ParentWeightsCsv(const ParentWeights& w);

/// Everything but the rows: scenario facts, the predicted Gaussian, the true pose (or null),
/// and the effective sample size 1 / sum w^2 of each weighting (ess_single_cluster, ess_rb_phd,
/// ess_single_feature).
nlohmann::json ParentWeightsJson(const ParentWeights& w);

/// The three ESS of one compared step.
struct StepEss {
  std::size_t step = 0;
  std::size_t measurements = 0;
  std::size_t map_components = 0;
  double single_cluster = 0.0;
  double rb_phd = 0.0;
  double single_feature = 0.0;
};

/// CompareParentWeightingAtStep at each of `steps` (increasing, each >= 1) with one filter run:
/// the predicted states, parents and scans are identical for the three weightings. Steps without
/// measurements are skipped.
std::vector<StepEss> CompareParentWeightingOverSteps(const datasets::Scenario& scenario,
                                                     const ParentWeightsSettings& settings,
                                                     const std::vector<std::size_t>& steps);

/// `step,measurements,map_components,ess_single_cluster,ess_rb_phd,ess_single_feature`.
std::string StepEssCsv(const std::vector<StepEss>& rows);

/// Paired comparisons over the steps: mean ESS of each weighting and the Wilcoxon signed-rank
/// tests of single-cluster minus single-feature and single-cluster minus (46).
nlohmann::json StepEssJson(const std::vector<StepEss>& rows);

}  // namespace phdslam::validation
