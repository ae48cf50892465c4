// The filtering bound (docs/algorithms/pcrb.md section 2): the posterior Cramer-Rao bound on the
// pose at step k given the data up to k, the map marginalised in, computed as the covariance
// form of Tichavsky et al.'s information recursion at the truth. The joint covariance of the pose
// and the landmarks detected so far is propagated: the prediction adds F_u Q_u F_u^T (no inverse
// of the rank-2 pose-space noise is ever formed), a landmark enters at its first detection with
// the exact flat-prior (zero-information) initialisation, and every detection is a Kalman
// update with the Cholesky-solved innovation covariance, the result symmetrised.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "reference/pcrb/linearised_slam.h"
#include "src/core/types.h"

namespace phdslam::reference::pcrb {

struct FilteringBound {
  std::vector<Mat3> pose_covs;  ///< per step, the bound on the pose covariance
  /// After the last step, per landmark: whether it was ever detected, and its 2x2 bound.
  std::vector<bool> landmark_seen;
  std::vector<Mat2> landmark_covs;
  /// The final joint covariance of the detected landmarks in landmark order, 2 per landmark
  /// (zero rows and columns for landmarks never detected).
  Eigen::MatrixXd map_cov;
};

/// Throws std::invalid_argument when a detection's landmark index is out of range or a
/// covariance is not positive definite (naming the step).
FilteringBound ComputeFilteringBound(const LinearisedSlam& model);

}  // namespace phdslam::reference::pcrb
