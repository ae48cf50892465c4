// Parameters of the per-particle GM-PHD map (docs/algorithms/phd-slam.md section 3, section 7).
// Defaults are the paper's synthetic-scenario values. Options named `reference_*` select the
// behaviour of the authors' code where it departs from the paper's text or from Vo & Ma; each is
// on by default because the published numbers come from that code.
#pragma once

#include <cmath>

namespace phdslam::phd {

struct MapParams {
  /// Log-weight of a birth component: ln(1e-6).
  double birth_log_weight = std::log(1e-6);
  /// Gate on the squared Mahalanobis distance, accepted when strictly below: chi2_2 at 1 - 1e-9.
  double gate_threshold = 41.4465;
  /// Components with log-weight below this are pruned (the leading one is always kept).
  double prune_log_weight = std::log(1e-6);
  /// U: merge distance threshold, and the covariance-trace threshold of the spread kill.
  double merge_threshold = 50.0;
  /// Log-weight a spread-killed component receives: ln(1e-18).
  double spread_kill_log_weight = -41.4465;

  /// Reference code: the merge distance uses the leading component's covariance P_i.
  /// false: Vo & Ma (2006) Table II, which uses the candidate's covariance P_j.
  bool reference_merge_leading_covariance = true;
  /// Reference code: a component may join several clusters (it is not checked for having already
  /// been merged). false: each component joins at most one cluster.
  bool reference_merge_double_membership = true;
  /// Reference code: merged components whose covariance trace exceeds U are given
  /// spread_kill_log_weight. false: no spread kill.
  bool reference_spread_kill = true;
  /// Reference code (and the paper): only measurements that gate with no component are births.
  /// false: every measurement of the previous step becomes a birth, as in earlier PHD-SLAM work.
  bool reference_births_from_ungated_only = true;
  /// Reference code (and the paper's eq. 46): the particle weight omits the -sum(pD eta) term of
  /// the exact Poisson likelihood. false: include it.
  bool reference_omit_missed_detection_mass = true;
};

}  // namespace phdslam::phd
