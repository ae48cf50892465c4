// Gated nearest-neighbour association of one scan against a map with marginal covariances, for
// the fixed-lag smoother's own association (fixed_lag_smoother.h): each measurement z_j and
// landmark i get the innovation nu = wrap(h(x, m_i) - z_j) and its covariance
// S = Hx Px Hx^T + Hm P_i Hm^T + Hm C_i Hx^T + Hx C_i^T Hm^T + R from the pose's and the
// landmark's marginal covariances and their cross-covariance C_i = Cov(m_i, x). In the window the
// pose and the landmarks it sees share most of their uncertainty (the drift of the whole window),
// so leaving C_i out would widen the gate by that drift, in which clutter then collects the
// detections that confirm it; C_i is zero for a marginalised landmark, whose correlation with the
// window was dropped at marginalisation (a wider, conservative gate). A pair is a candidate when
// nu^T S^-1 nu < gate_chi2. Candidates are assigned greedily in increasing distance, each landmark
// and each measurement at most once. Outliers that pass the gate are left to the robust loss of the
// detection factors.
#pragma once

#include <vector>

#include "src/core/types.h"

namespace phdslam::reference {

struct AssociationCandidate {
  int label = 0;
  Landmark mean = Landmark::Zero();
  Mat2 cov = Mat2::Zero();  ///< marginal covariance
  /// Cross-covariance with the pose, Cov(m, x); zero when unknown (a marginalised landmark).
  Eigen::Matrix<double, 2, 3> pose_cross = Eigen::Matrix<double, 2, 3>::Zero();
};

/// Per measurement, the label of the landmark it is associated with, or -1.
std::vector<int> GatedNearestNeighbour(const Pose& x, const Mat3& pose_cov,
                                       const std::vector<Measurement>& measurements,
                                       const std::vector<AssociationCandidate>& candidates,
                                       const Mat2& noise_cov, double gate_chi2);

}  // namespace phdslam::reference
