// Re-localisation with evidence from several scans after a long stretch of dead reckoning
// (README.md, "Re-localisation after dead reckoning").
//
// When the pose's marginal position standard deviation exceeds a threshold, one scan of one or
// two detections is matched by nearest neighbour with a wrong cluster of landmarks as readily as
// with the right one: both are jointly consistent under the wide pose covariance. Instead the
// detections of the next few scans are collected as inverse-model points from the dead-reckoned
// poses (so the odometry carries them into one frame), and the rigid transform that lays them on
// the map is searched for:
//
// * Hypotheses: every pair of points at least two inlier distances apart, matched with every
//   ordered pair of map landmarks whose distance agrees within the inlier distance, gives a
//   rotation and translation. A hypothesis is kept only when the newest pose it implies lies
//   within the pose gate of the dead-reckoned pose (chi-square, 3 dof, on its marginal
//   covariance).
// * Score: the points within the inlier distance of a landmark after the transform (each point
//   to its nearest landmark), the inliers, less prior_weight times half the squared Mahalanobis
//   distance of the implied pose from the dead-reckoned one (0: the inliers alone).
// * Uniqueness: the best hypothesis needs at least three inliers (one beyond the pair that
//   defines it) and must beat every rival by `margin` in score; a rival assigns some point to a
//   landmark other than the best's. Otherwise the match is refused.
// * The accepted transform is refined by least squares (2-D Procrustes) on its inliers.
#pragma once

#include <vector>

#include "src/core/types.h"

namespace phdslam::reference {

struct RelocalisationOptions {
  double inlier_distance = 0.5;  ///< a point within this of a landmark is an inlier (m)
  int margin = 2;                ///< inliers by which the best hypothesis must beat every rival
  /// Score of a hypothesis: inliers - prior_weight * d2 / 2, d2 the Mahalanobis distance of
  /// the pose it implies from the dead-reckoned one; 0: inliers alone.
  double prior_weight = 0.0;
  double pose_gate_chi2 = 16.27;  ///< the implied pose within this of the dead-reckoned one (3 dof)
};

/// A rigid correction of the plane: p -> R(theta) p + t.
struct RigidCorrection {
  Vec2 translation = Vec2::Zero();
  double rotation = 0.0;
};

Pose ApplyCorrection(const RigidCorrection& c, const Pose& x);

struct RelocalisationMatch {
  bool found = false;
  /// Not found because a rival explains the points (nearly) as well as the best, which has at
  /// least three inliers: the map admits several corrections.
  bool ambiguous = false;
  RigidCorrection correction;
  std::vector<int> landmark;  ///< per point: its map index, or kUnassociated
  int best_inliers = 0;
  int rival_inliers = 0;  ///< the best rival's inliers (0 when none)
  double baseline = 0.0;  ///< largest distance between two inliers (m)
};

/// Matches `points` (detections as inverse-model points from the dead-reckoned poses) with the
/// `map` landmarks; `newest` and `newest_cov` are the dead-reckoned newest pose and its marginal
/// covariance. Throws std::invalid_argument for a non-positive inlier distance, margin or gate.
RelocalisationMatch MatchPointsToMap(const std::vector<Landmark>& points,
                                     const std::vector<Landmark>& map, const Pose& newest,
                                     const Mat3& newest_cov, const RelocalisationOptions& options);

}  // namespace phdslam::reference
