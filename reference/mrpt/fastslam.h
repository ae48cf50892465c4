// "fastslam1" / "fastslam2": FastSLAM 1.0 and 2.0 with per-particle unknown data association and a
// landmark existence counter against clutter, built on MRPT's particle-filter engine.
//
// MRPT 2.5 has no FastSLAM for range-bearing landmarks (its RBPF map builder cannot insert
// bearing-range observations into a landmark map; see README.md), so the filter is assembled from
// MRPT's parts:
//   MRPT's:  mrpt::bayes::CParticleFilter (executeOn drives the proposal/update callback selected
//            by pfStandardProposal or pfOptimalProposal, then normalises the weights),
//            CParticleFilterData / CParticleFilterDataImpl (particle storage, weights, ESS,
//            substitution), CParticleFilterCapable::performResampling (the resampling schemes),
//            mrpt::slam::data_association_independent_predictions (FastSLAM 1.0) and
//            data_association_full_covariance (FastSLAM 2.0) for each particle's association.
//   Built here: the particle contents and both proposals (motion-model sampling; the
//            EKF-linearised measurement-conditioned pose proposal of FastSLAM 2.0), the weights,
//            the landmark EKFs, landmark creation and the existence counter, the ESS test, the
//            estimates (best particle, weighted pose spread) and every random draw except
//            resampling.
//   Covariances: StepOutput::pose_cov is the weighted particle spread (the classical
//            particle NEES). pose_mean_rb / pose_cov_rb (Rao-Blackwellised) are the moments of
//            the mixture over particles of the Gaussian each particle drew its pose from
//            (FastSLAM 1.0: the predicted Gaussian; 2.0: the measurement-conditioned one), weighted
//            by the weights carried into the step; none for a step with a single time stamp.
//            The NIS is the estimate's (highest-weight particle's) associated measurements with
//            the innovation covariances its weight used (fastslam_particle.h).
#pragma once

#include <cstdint>
#include <memory>

#include "datasets/scenario.h"
#include "reference/mrpt/fastslam_options.h"
#include "reference/mrpt/fastslam_particle.h"
#include "src/core/random.h"
#include "src/filters/estimator.h"

namespace phdslam::reference {

class FastSlam final : public filters::OnlineEstimator {
 public:
  /// Throws std::invalid_argument for particles < 1, invalid options or a missing motion model.
  FastSlam(filters::EstimatorContext context, int particles, std::uint64_t stream_seed,
           FastSlamOptions options = {});
  ~FastSlam() override;
  FastSlam(const FastSlam&) = delete;
  FastSlam& operator=(const FastSlam&) = delete;

  /// One step: MRPT's CParticleFilter::executeOn runs the proposal, association and update of
  /// every particle and normalises the weights; then the estimate is taken from the highest-weight
  /// particle and, when ESS <= ess_threshold_fraction N (N > 1), MRPT resamples.
  /// pose_cov is the weighted spread of the particle poses (set only when N > 1).
  filters::StepOutput Step(const datasets::StepData& step) override;

  /// The confirmed landmarks of the particle that had the highest weight at the last step.
  [[nodiscard]] filters::MapEstimate Map() const override;

  /// Every landmark of that particle, tentative ones included.
  [[nodiscard]] const FastSlamParticle& BestParticle() const { return best_; }
  [[nodiscard]] const FastSlamOptions& options() const { return options_; }

 private:
  filters::EstimatorContext context_;
  FastSlamOptions options_;
  int particles_;
  RandomStream stream_;
  struct MrptParts;  // MRPT's CParticleFilter and the particle set (fastslam.cc)
  std::unique_ptr<MrptParts> mrpt_;
  FastSlamParticle best_;
  int step_index_ = 0;
};

}  // namespace phdslam::reference
