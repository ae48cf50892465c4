// Gated nearest-neighbour association of one scan against a map with marginal covariances, for
// the fixed-lag smoother's own association (fixed_lag_smoother.h): each measurement z_j and
// landmark i get the innovation nu = wrap(h(x, m_i) - z_j) and its covariance
// S = Hx Px Hx^T + Hm P_i Hm^T + R from the pose's and the landmark's marginal covariances (their
// cross-covariance left out, which widens S when they are positively correlated, as after a
// shared detection history); a pair is a candidate when nu^T S^-1 nu < gate_chi2. Candidates are
// assigned greedily in increasing distance, each landmark and each measurement at most once.
// Outliers that pass the gate are left to the robust loss of the detection factors.
#pragma once

#include <vector>

#include "src/core/types.h"

namespace phdslam::reference {

struct AssociationCandidate {
  int label = 0;
  Landmark mean = Landmark::Zero();
  Mat2 cov = Mat2::Zero();  ///< marginal covariance
};

/// Per measurement, the label of the landmark it is associated with, or -1.
std::vector<int> GatedNearestNeighbour(const Pose& x, const Mat3& pose_cov,
                                       const std::vector<Measurement>& measurements,
                                       const std::vector<AssociationCandidate>& candidates,
                                       const Mat2& noise_cov, double gate_chi2);

}  // namespace phdslam::reference
