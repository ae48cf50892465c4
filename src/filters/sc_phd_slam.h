// Single-cluster PHD SLAM (Lee, Clark & Salvi, "SLAM with Single Cluster PHD Filters", ICRA 2012).
//
// The vehicle is the parent process of a single-cluster point process: a Dirac mixture of N pose
// samples with log-weights. Each parent carries the GM-PHD map of its daughter (landmark) process.
// One step:
//  1. Births: the parent's pending measurements of the previous step become components at the
//     parent's pose (GmPhdMap::AddBirths, birth log-weight ln 0.01 by default). By default every
//     measurement of the previous step is a birth, as in the paper
//     (MapParams::reference_births_from_ungated_only = false).
//  2. Shotgun prediction: every parent is predicted into M children, each with a copy of the
//     parent's map. A child's pose is drawn by sampling the control noise: once per step a
//     regularising jitter N(0, Q_n) is added to the pose, then every sub-interval is propagated
//     with the motion model at the control u + N(0, Q_u) (kControlNoise, the default).
//     kLinearisedGaussian instead samples from the linearised Gaussian (mean f, covariance
//     Fx (P + Q_n) Fx^T + Fu Q_u Fu^T per sub-interval) that the RB-PHD-SLAM family propagates.
//     A step with a single time stamp has no propagation and M = 1 (the copies would be equal).
//  3. Daughter update at the child's pose (GmPhdMap::Update) and parent weight from the
//     single-cluster multi-object likelihood (the paper's eq. 33):
//       log w += -sum_i pD_i w_i + sum_j log(lambda_c + sum_i pD_i w_i N(z_j; h(m_i, x), S_i)),
//     i.e. MapParams::reference_omit_missed_detection_mass = false. A scan with no measurements
//     still applies the missed-detection part (w_i <- (1 - pD_i) w_i and log w -= sum pD_i w_i)
//     unless empty_scan_update is false, where the reference code skips the update.
//  4. Pruning: the N x M children are cut back to the N highest log-weights (ties to the lower
//     child index), kept in child order, and their log-weights normalised. This is selection,
//     not resampling: weights are kept, so StepDiagnostics::resampled is always false.
//  5. Map reduction (GmPhdMap::Reduce) of the survivors at their poses.
//  6. Estimates: the pose is the expected a posteriori pose, the weighted mean of the parents;
//     the heading is averaged as an unwrapped number because headings are never wrapped in this
//     project. The map comes from the highest-weight parent (first on ties): its
//     round(sum of component weights) highest-weight components, active and passive.
// Every random number comes from one RandomStream seeded by the constructor's stream seed.
// Covariances: pose_cov is the weighted spread of the parents about the estimate.
// pose_mean_rb / pose_cov_rb (Rao-Blackwellised) are the moments of the mixture over parents of
// each parent's linearised predicted Gaussian (the density kLinearisedGaussian samples from, and
// the Gaussian approximation of kControlNoise's draws), weighted by the parent weights carried
// into the step; a step with a single time stamp has no propagation and reports none. The NIS is
// that of the highest-weight parent's daughter update (GmPhdMap::Update's selection of the
// measurements it explains best by a landmark).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "src/core/random.h"
#include "src/core/types.h"
#include "src/filters/estimator.h"
#include "src/filters/innovation_stats.h"
#include "src/filters/pose_mixture_moments.h"
#include "src/filters/sc_phd_slam_params.h"
#include "src/phd/gaussian_component.h"
#include "src/phd/gm_phd_map.h"
#include "src/phd/map_params.h"

namespace phdslam::filters {

/// One pose sample of the parent process with its daughter map.
struct ScParent {
  Pose pose = Pose::Zero();
  double log_weight = 0.0;
  phd::GmPhdMap map;
  std::vector<Measurement> births;  ///< measurements that become births at the next step
  InnovationStats nis;              ///< NIS of the daughter update of the last step
};

/// A child of the last step before pruning (diagnostics and tests).
struct ScChild {
  int parent = 0;  ///< index of the parent it was predicted from
  Pose pose = Pose::Zero();
  double log_weight = 0.0;  ///< parent log-weight + single-cluster log-likelihood (unnormalised)
  bool kept = false;
};

/// The daughter update of one child: GmPhdMap::Update at `pose`, returning the log-likelihood
/// increment of the parent weight. With no measurements and `empty_scan_update`, components with
/// pD > 0 get log(1 - pD) added and the increment is -sum pD w; otherwise it is whatever
/// GmPhdMap::Update returns. `ungated` receives the measurement indices that become births;
/// `nis` (when given) the update's NIS (zero for an empty scan).
double UpdateDaughterMap(phd::GmPhdMap& map, const Pose& pose,
                         std::span<const Measurement> measurements,
                         const models::SensorModel& sensor, const phd::MapParams& params,
                         bool empty_scan_update, std::vector<int>* ungated,
                         InnovationStats* nis = nullptr);

/// The map estimate of one daughter process: round(sum of component weights) components of the
/// active and passive lists, highest log-weight first (stable on ties, active before passive).
std::vector<phd::GaussianComponent> CardinalityMapEstimate(const phd::GmPhdMap& map);

class ScPhdSlam final : public OnlineEstimator {
 public:
  /// Throws std::invalid_argument when particles or shotgun is below 1, the context has no motion
  /// model, or a noise covariance is not symmetric positive semi-definite.
  ScPhdSlam(EstimatorContext context, ScPhdSlamParams params, std::uint64_t stream_seed);

  StepOutput Step(const StepData& step) override;
  [[nodiscard]] MapEstimate Map() const override;

  /// The N parents after the last step, log-weights normalised.
  [[nodiscard]] const std::vector<ScParent>& parents() const { return parents_; }
  /// Index of the parent the last map estimate came from.
  [[nodiscard]] int best_parent() const { return best_; }
  /// All children of the last step, in child order (parent-major), before pruning.
  [[nodiscard]] const std::vector<ScChild>& last_children() const { return children_; }

 private:
  /// Predicts `pose` over the step's sub-intervals with the normals `xi` (3 + 2 per sub-interval).
  [[nodiscard]] Pose SamplePose(const Pose& pose, const StepData& step,
                                std::span<const double> xi) const;
  /// The linearised predicted Gaussian of `pose` over the step (Q_n once, then Fx P Fx^T +
  /// Fu Q_u Fu^T per sub-interval); log_weight 0.
  [[nodiscard]] PoseMoments LinearisedPrediction(const Pose& pose, const StepData& step) const;
  /// Moments of the mixture of the parents' linearised predicted Gaussians (before sampling).
  [[nodiscard]] std::optional<PoseMoments> PredictedMixtureMoments(const StepData& step) const;

  EstimatorContext context_;
  ScPhdSlamParams params_;
  RandomStream rng_;
  Mat2 control_noise_sqrt_;
  Mat3 regularisation_sqrt_;
  std::vector<ScParent> parents_;
  std::vector<ScChild> children_;
  int best_ = 0;
  std::vector<phd::GaussianComponent> last_map_;
};

}  // namespace phdslam::filters
