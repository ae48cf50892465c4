// The pose proposal of delta-GLMB-SLAM 2.0 (docs/algorithms/glmb-slam.md section 6.3, the optimal
// kernel): the associations sampled at the predicted pose (with the pose uncertainty in every
// innovation covariance) each give an EKF update of the predicted pose Gaussian with their detected
// pairs; the weighted updates are collapsed into one Gaussian by moment matching or kept as a
// mixture.
#pragma once

#include <span>

#include "src/filters/gaussian_mixture_proposal.h"
#include "src/glmb/glmb_slam_params.h"
#include "src/glmb/joint_update.h"

namespace phdslam::glmb {

struct KernelProposal {
  filters::GaussianMixtureProposal mixture;
  /// log of the sum of the samples' unnormalised weights (the literal eq. 33 increment, A4 (a)).
  double log_marginal = 0.0;
};

/// The pose EKF of one association: starting from N(mean, cov), each detected row (entry e,
/// measurement j) in row order updates the pose with H_x at the current mean and noise
/// H_m P_e H_m' + R (the entry's heaviest component), Joseph form, symmetrised.
void UpdatePoseWithAssociation(const JointProblem& problem, const JointProblem::Parent& parent,
                               std::span<const int> gamma,
                               std::span<const Measurement> measurements, const Mat2& noise_cov,
                               Pose& mean, Mat3& cov);

/// The proposal from `samples` (from a problem built at `mean` with pose_cov = `cov`). With no
/// samples it is N(mean, cov) and log_marginal = -inf.
KernelProposal BuildKernelProposal(const JointProblem& problem,
                                   std::span<const SampledAssociation> samples, const Pose& mean,
                                   const Mat3& cov, std::span<const Measurement> measurements,
                                   const Mat2& noise_cov, KernelAssociations associations,
                                   KernelForm form);

}  // namespace phdslam::glmb
