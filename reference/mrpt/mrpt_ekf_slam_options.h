// The options of "mrpt-ekf" (MrptEkfSlam, mrpt_ekf_slam.h), without MRPT: the registry resolves
// and validates them in processes that never load MRPT.
#pragma once

#include "reference/mrpt/association_options.h"

namespace phdslam::reference {

struct MrptEkfSlamOptions {
  AssociationMethod association = AssociationMethod::kJcbb;
  AssociationMetric metric = AssociationMetric::kMahalanobis;
  /// Individual-compatibility gate of MRPT's association: a pairing is a candidate when its squared
  /// Mahalanobis distance is below chi2inv(ic_chi2_quantile, 2); 0.999 gives 13.82. A measurement
  /// with no candidate becomes a new landmark, for good (MRPT never deletes landmarks).
  double ic_chi2_quantile = 0.999;
  /// Post-processing only: PostProcessedMap() keeps the landmarks associated at least this many
  /// times after their creation.
  int min_associations = 3;
  /// Stock CRangeBearingKFSLAM2D looks up association candidates with a KD-tree over the predicted
  /// (range, bearing) means and stops at the first one, in Euclidean (m, rad) order, whose squared
  /// Mahalanobis distance exceeds 6 chi2inv(q, 2). Range dominates that order, so a landmark at a
  /// similar range but another bearing can hide the right one, which then becomes a duplicate
  /// landmark. false (default): the same MRPT association routine is called with the KD-tree off,
  /// so every predicted landmark is tested. true: stock MRPT behaviour.
  bool mrpt_kdtree_candidates = false;
  /// Track deletion, NOT part of MRPT (0 = off = stock MRPT): a landmark that has been associated
  /// with fewer than prune_min_associations measurements when it is this many steps old is
  /// removed from the filter state (mean, covariance rows and columns, id map). Stock MRPT keeps
  /// every clutter measurement as a landmark forever: on the paper's scenario (about 4.75 clutter
  /// points per scan, 4000 scans) the state would reach about 19,000 landmarks (an 11 GB
  /// covariance), and the gates of the clutter landmarks soon cover the field of view, so that
  /// about a third of new clutter points get associated with old ones.
  int prune_after_steps = 0;
  int prune_min_associations = 2;
  /// MRPT's kfEKFNaive update writes P <- (I - K H) P, which does not keep P symmetric; over
  /// thousands of updates the asymmetry grows until P is indefinite and the filter explodes (seen
  /// on the paper's scenario, seed 2, near step 3778). true (default): P <- (P + P^T) / 2 after
  /// every step, a deviation from MRPT; false: stock MRPT.
  bool symmetrize_covariance = true;

  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

}  // namespace phdslam::reference
