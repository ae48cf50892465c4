// The options of "fastslam1" / "fastslam2" (FastSlam, fastslam.h), without MRPT: the registry
// resolves and validates them in processes that never load MRPT.
#pragma once

#include <optional>
#include <string>

#include "reference/mrpt/association_options.h"
#include "src/core/types.h"

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

}  // namespace phdslam::reference
