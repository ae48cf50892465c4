// Rao-Blackwellised PHD-SLAM: the particle-filter skeleton (particle_filter.h) over per-particle
// GM-PHD maps; the family members differ only in their ImportanceDensity
// (docs/algorithms/phd-slam.md section 2-6).
//
// Pose covariances in StepOutput: pose_cov is the weighted particle spread about the estimate
// (the classical particle NEES); pose_cov_rb / pose_mean_rb the Rao-Blackwellised mixture
// (particle_filter.h) of each particle's proposal with the carried-in weights, i.e. for
// PHD-SLAM 3.0 its GM IPL density, for 2.0a the moment-matched EKF conditional, for 2.0b the
// joint-IPL pose marginal and for 1.0 the predicted Gaussian (its proposal is the prior, so its
// RB covariance ignores the step's measurements). NIS: StepDiagnostics::nis_sum of the estimate's
// particle, from its GM-PHD update (phd::PhdUpdateResult::nis_sum).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "src/core/byte_tally.h"
#include "src/filters/estimator.h"
#include "src/filters/importance_density.h"
#include "src/filters/particle_filter.h"
#include "src/filters/phd_slam_params.h"
#include "src/phd/gm_phd_map.h"

namespace phdslam::filters {

/// A particle's map: the GM-PHD intensity and the previous scan's ungated measurements, which
/// become births at the next prediction.
struct PhdParticleMap {
  phd::GmPhdMap gm;
  std::vector<Measurement> births;

  /// Adds the heap bytes of the map to `tally` (storage shared with other maps counted once).
  void CountBytes(ByteTally& tally) const {
    gm.CountBytes(tally);
    tally.AddVector(births);
  }
};

/// The GM-PHD map model of the skeleton:
///  - before prediction, the pending births are added at the pose the scan was taken from;
///  - the landmark view is the active component list;
///  - the update is the GM-PHD update at the sampled pose (its log-likelihood, or the
///    RB-PHD-SLAM strategy of PhdSlamParams::weighting, added to the weight), the ungated
///    measurements kept as next births, then the hypothesis reduction;
///  - the estimate is every component with log-weight above ln((1 - pD)^2) (or the parameter).
class PhdMapModel {
 public:
  using Map = PhdParticleMap;
  /// A copy of the best particle's mixture (cheap: it shares the passive chunks); the
  /// thresholded estimate is extracted only when the map is asked for (ToMapEstimate).
  using Snapshot = phd::GmPhdMap;

  PhdMapModel(const EstimatorContext& context, const PhdSlamParams& params);

  [[nodiscard]] Map InitialMap() const { return {}; }
  void BeginStep(const StepData& /*step*/) {}
  void BeforePrediction(Map& map, const Pose& pose) const;
  [[nodiscard]] MapView View(const Map& map) const { return {map.gm.active(), {}}; }
  /// Also adds the NIS of the GM-PHD update (phd::PhdUpdateResult::nis_sum: per measurement the
  /// best-explaining component, when it beats clutter) to `nis`.
  void Update(Map& map, const Pose& pose, const StepData& step, double& log_weight,
              InnovationStats& nis) const;
  void Update(Map& map, const Pose& pose, const StepData& step, double& log_weight) const {
    InnovationStats unused;
    Update(map, pose, step, log_weight, unused);
  }
  [[nodiscard]] Snapshot Estimate(const Map& map) const { return map.gm; }
  [[nodiscard]] MapEstimate ToMapEstimate(const Snapshot& snapshot) const;
  [[nodiscard]] int ComponentCount(const Map& map) const { return static_cast<int>(map.gm.size()); }

 private:
  /// Keeps the ungated measurements as next births, then reduces the mixture.
  void KeepBirthsAndReduce(Map& map, const Pose& pose, const StepData& step,
                           const std::vector<int>& ungated) const;

  models::SensorModel sensor_;
  phd::MapParams map_params_;
  RbPhdWeighting weighting_;
  double estimate_threshold_;
};

using RbPhdSlam = ParticleFilter<PhdMapModel>;
using PhdParticle = RbPhdSlam::ParticleType;

/// The skeleton parameters of a PHD-SLAM parameter set.
ParticleFilterParams SkeletonParams(const PhdSlamParams& params);

/// A PHD-SLAM filter with the given importance density.
std::unique_ptr<RbPhdSlam> MakeRbPhdSlam(EstimatorContext context, const PhdSlamParams& params,
                                         std::unique_ptr<ImportanceDensity> density,
                                         std::uint64_t stream_seed);

}  // namespace phdslam::filters

extern template class phdslam::filters::ParticleFilter<phdslam::filters::PhdMapModel>;
