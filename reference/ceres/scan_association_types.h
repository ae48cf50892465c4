// What the association of one scan with an optimised map is made of: the map as the association
// sees it and the per-measurement result, shared by the gated nearest neighbour
// (scan_association.h) and joint compatibility branch and bound (joint_compatibility.h).
#pragma once

#include <vector>

#include "src/core/types.h"

namespace phdslam::reference {

/// A map landmark as the association sees it: its mean, marginal covariance and (when known)
/// cross-covariance with the pose, Cov(m, x).
struct MapLandmark {
  Landmark mean = Landmark::Zero();
  Mat2 cov = Mat2::Identity();
  Eigen::Matrix<double, 2, 3> pose_cross = Eigen::Matrix<double, 2, 3>::Zero();
  /// pD at the pose (the likelihood test against a new landmark; 1 when unknown).
  double detection_probability = 1.0;
};

/// Per measurement of the scan: the map index (kUnassociated when no landmark passed the gate or
/// the nearest one went to a closer measurement), the squared Mahalanobis distance (0 when
/// unassociated) and how many landmarks passed its gate (and the likelihood test when on).
struct ScanAssociation {
  std::vector<int> landmark;
  std::vector<double> mahalanobis2;
  std::vector<int> gated;  ///< landmarks inside the measurement's gate
};

}  // namespace phdslam::reference
