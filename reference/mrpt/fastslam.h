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
#include <optional>
#include <string>

#include "datasets/scenario.h"
#include "reference/mrpt/association_options.h"
#include "reference/mrpt/fastslam_particle.h"
#include "src/core/random.h"
#include "src/filters/estimator.h"

namespace phdslam::reference {

enum class FastSlamProposal {
  kMotionModel,  ///< FastSLAM 1.0: sample the pose from the motion model (pfStandardProposal)
  /// FastSLAM 2.0: sample from the motion prior conditioned on the associated measurements by
  /// sequential EKF updates (pfOptimalProposal)
  kMeasurementConditioned,
};

/// MRPT's resampling schemes (CParticleFilter::TParticleResamplingAlgorithm).
enum class ResamplingScheme { kMultinomial, kResidual, kStratified, kSystematic };

std::string ToString(ResamplingScheme s);
/// "multinomial" / "residual" / "stratified" / "systematic"; throws std::invalid_argument naming
/// `field`.
ResamplingScheme ParseResamplingScheme(const std::string& s, const std::string& field);

struct FastSlamOptions {
  FastSlamProposal proposal = FastSlamProposal::kMeasurementConditioned;
  /// Per-particle association: maximum likelihood, i.e. MRPT's nearest neighbour under the
  /// matching-likelihood metric, one measurement per landmark.
  AssociationMethod association = AssociationMethod::kNearestNeighbour;
  AssociationMetric metric = AssociationMetric::kMatchingLikelihood;
  /// New-landmark threshold: a measurement is a candidate for a landmark when the squared
  /// Mahalanobis distance is below chi2inv(ic_chi2_quantile, 2) (0.999 gives 13.82); a
  /// measurement with no candidate creates a new landmark.
  double ic_chi2_quantile = 0.999;
  /// Log-likelihood credited to a measurement that creates a landmark. Unset: the density of a
  /// point uniform over the field of view in (r, phi), -log(2 fov_half_angle fov_range).
  std::optional<double> new_landmark_log_likelihood;
  /// A landmark is confirmed (and enters Map()) once associated this many times after creation.
  /// With 1, a clutter landmark that catches one later clutter point is confirmed and, once out of
  /// view, never predicted visible again, so it stays in the map; 2 makes that rare.
  int confirm_associations = 2;
  /// An unconfirmed landmark is removed this many steps after its creation.
  int tentative_steps = 4;
  /// Resample when ESS <= ess_threshold_fraction N (the paper's synthetic setting is 0.2).
  double ess_threshold_fraction = 0.2;
  ResamplingScheme resampling = ResamplingScheme::kSystematic;
  /// Added to the predicted pose covariance once per step with propagation
  /// (docs/algorithms/models.md section 2.4: Q_n regularises the rank-2 control noise).
  Vec3 pose_regulariser_diag = Vec3(1e-9, 1e-9, 1e-18);

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

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
