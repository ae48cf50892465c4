// Data-association accuracy as a confusion matrix over measurements, read from what the filters
// output (StepOutput::association) and the scenario's hidden origin labels. The PHD-SLAM 3.0 paper
// reports it as TPR and TNR (PHD 2.0b: 0.9223 / 0.9980; PHD 3.0: 0.9829 / 0.9984).
//
// Definition, per measurement j of a step with origin label o_j and reported association a_j
// (the mean of the map landmark the estimate associated z_j with, or NaN for "clutter / new
// landmark"):
//   * Positive: o_j is a landmark index whose landmark was measured at an earlier step
//     (seen_before[o_j]), so the map should hold a component for it and the filter should
//     associate z_j with that component.
//       TP: a_j is not NaN, the true landmark nearest to a_j is o_j (smallest index on ties) and
//           ||a_j - truth[o_j]|| <= max_distance;
//       FN: otherwise (not associated, associated with another landmark's component, or with a
//           component farther than max_distance from the origin).
//   * Negative: o_j is clutter (datasets::kClutter).
//       TN: a_j is NaN (not associated);
//       FP: a_j is not NaN (clutter explained by a map landmark).
//   * First sighting: o_j is a landmark index not measured at any earlier step. It is neither
//     positive nor negative, since no map component can exist for it yet; it is counted in
//     `first_sightings`, and in `first_sightings_associated` when the filter nevertheless
//     associated it with some component.
// A landmark measured twice in one step is a first sighting both times if it had not been seen
// before that step; seen_before is updated only after the whole step is scored.
//
// An empty association vector for a step with measurements means the estimator reported no
// association for that step (OnlineEstimator's "does not associate"; RbPhdSlam also reports none
// at a step whose importance density fell back to the prior, e.g. while its map is empty). Those
// measurements are not scored: they are counted in `unreported`, and seen_before is still
// updated. An estimator that never associates thus ends with NaN rates and every measurement
// unreported.
//
// max_distance guards against crediting an association with a component that is merely the
// nearest to the right landmark from far away. It also turns map drift into false negatives: a
// correctly associated landmark whose estimate is more than max_distance from the truth counts
// as FN. Pass infinity to score the landmark identity alone.
#pragma once

#include <vector>

#include "src/core/types.h"

namespace phdslam::validation {

struct AssociationCounts {
  long tp = 0;
  long fn = 0;
  long tn = 0;
  long fp = 0;
  long first_sightings = 0;
  long first_sightings_associated = 0;
  long unreported = 0;  ///< measurements of steps with an empty association vector

  /// TP / (TP + FN); NaN when there is no positive.
  [[nodiscard]] double tpr() const;
  /// TN / (TN + FP); NaN when there is no negative.
  [[nodiscard]] double tnr() const;
  /// Adds another set of counts (pooling over steps, runs or seeds).
  AssociationCounts& operator+=(const AssociationCounts& other);
};

/// Scores one step and then marks every landmark measured in it as seen.
///   origins      hidden labels of the step's measurements (landmark index >= 0 or kClutter);
///   association  per measurement the associated landmark mean or NaN (StepOutput::association);
///   truth        the true landmarks;
///   seen_before  which true landmarks were measured at an earlier step, kept by the caller across
///                steps; an empty vector is taken as "none yet" and sized to truth.size().
/// Throws std::invalid_argument when association is neither empty nor of origins' size, when
/// seen_before's size is neither 0 nor truth.size(), when a label is below kClutter (unknown
/// origin, e.g. real data) or not a truth index, when an association has one NaN and one number or
/// an infinite coordinate, or when max_distance is not positive (infinity is allowed). A throw
/// leaves counts and seen_before unchanged.
void AccumulateAssociation(const std::vector<int>& origins,
                           const std::vector<Landmark>& association,
                           const std::vector<Landmark>& truth, std::vector<bool>& seen_before,
                           double max_distance, AssociationCounts& counts);

}  // namespace phdslam::validation
