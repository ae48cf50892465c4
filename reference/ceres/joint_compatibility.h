// Joint compatibility branch and bound (JCBB) over one scan: the assignment of the scan's
// measurements to map landmarks (or to none: clutter or a new landmark) with the most pairs whose
// innovations are jointly compatible, ties broken by the lower joint Mahalanobis distance.
//
// * Candidates: the pairs inside the individual gate (scan_association.h), each landmark with its
//   marginal covariance Pm and, when known, its cross-covariance C = Cov(m, x) with the pose.
// * Joint innovation covariance of pairs a, b: S_ab = Hx_a Px Hx_b^T + Hx_a C_b^T Hm_b^T +
//   Hm_a C_a Hx_b^T + [a = b] (Hm_a Pm_a Hm_a^T + R). The pose's uncertainty is shared by every
//   pair, so a pose error shifts all innovations together: a set of pairs that needs two different
//   pose errors is not jointly compatible even when each pair is inside its gate.
// * Joint test: nu^T S^-1 nu below the chi-square quantile of 2p degrees of freedom (p pairs) at
//   the same tail probability as the individual gate, exp(-gate_chi2 / 2).
// * Search: depth first over the measurements that have candidates, each landmark's candidates in
//   increasing individual distance, then the null alternative; a branch that cannot reach the best
//   pair count is cut. At most max_nodes joint tests; past the limit every open branch takes the
//   null alternative, and the best complete assignment found is returned.
// * Likelihood objective (null_intensity > 0): instead of the most pairs, the least
//   -log [N(nu; 0, S) prod_pairs pD] - (measurements left out) log null_intensity, the same
//   likelihood the RFS filters weigh an association by (a pair against clutter or a new landmark
//   of that intensity); a branch is cut when its cost plus the least each remaining measurement
//   can add (the null cost, or 1/2 log det(2 pi R) for a pair) reaches the best.
#pragma once

#include <vector>

#include "reference/ceres/scan_association_types.h"
#include "src/core/types.h"

namespace phdslam::reference {

/// One pair inside the individual gate.
struct GatedPair {
  int measurement = 0;
  int landmark = 0;
  double d2 = 0.0;  ///< individual squared Mahalanobis distance
};

struct JointCompatibilityOptions {
  double gate_chi2 = 13.8;  ///< the individual gate (2 dof); sets the joint test's tail probability
  int max_nodes = 20000;    ///< joint compatibility tests per scan before the search stops
  /// 0: the most pairs (classic JCBB). > 0: the jointly compatible assignment of the least cost
  /// -log L, L = N(nu; 0, S) prod pD over the pairs times this intensity (per m per rad of
  /// measurement space: clutter or a new landmark) for each measurement left out.
  double null_intensity = 0.0;
};

/// The JCBB assignment of `scan` over the candidate `pairs`. ScanAssociation::gated counts each
/// measurement's candidates. Throws std::invalid_argument when gate_chi2 <= 0, max_nodes < 1 or
/// null_intensity < 0.
ScanAssociation JointCompatibleAssociation(const Pose& pose, const Mat3& pose_cov,
                                           const std::vector<MapLandmark>& map,
                                           const std::vector<Measurement>& scan, const Mat2& r,
                                           const std::vector<GatedPair>& pairs,
                                           const JointCompatibilityOptions& options);

/// The chi-square quantile with `dof` (even, >= 2) degrees of freedom whose upper tail holds
/// probability `tail` (in (0, 1)).
double ChiSquareQuantileEvenDof(int dof, double tail);

}  // namespace phdslam::reference
