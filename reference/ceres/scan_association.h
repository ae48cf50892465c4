// Scan-to-map data association for graph optimisation run in time order (the incremental batch
// smoother, README.md "Incremental solve"; usable by any smoother that keeps an optimised map).
//
// * Gating: measurement z at the pose (x, Px) against a map landmark (m, Pm), both with their
//   marginal covariances: nu = [z_r - h_r; wrap(z_phi - h_phi)],
//   S = Hx Px Hx^T + Hm Pm Hm^T + Hm C Hx^T + Hx C^T Hm^T + R, accepted when
//   nu^T S^-1 nu < gate_chi2 (strict), with C = Cov(m, x) the pose-landmark cross-covariance
//   when the caller knows it (the fixed-lag smoother's window) and zero otherwise; leaving it out
//   makes S larger (more conservative) for a landmark seen recently from a pose correlated with
//   the current one.
// * Likelihood against a new landmark (new_landmark_intensity > 0): a gated pair is admissible
//   only when pD N(nu; 0, S) >= new_landmark_intensity, i.e. when the landmark explains z better
//   than a new landmark or clutter of that intensity (per m per rad of measurement space) would.
//   Under a wide pose covariance (after a long stretch of dead reckoning) S spreads the
//   likelihood so thin that no landmark qualifies, however small its Mahalanobis distance, and
//   the measurement starts a landmark instead of re-localising the pose on one nearest neighbour.
// * Assignment: gated nearest neighbour over the whole scan (greedy global nearest neighbour):
//   candidate pairs in increasing Mahalanobis distance, ties broken by measurement then landmark
//   index, each measurement and each landmark used at most once; or (assignment =
//   kJointCompatibility) the jointly compatible assignment with the most pairs
//   (joint_compatibility.h). The solver then applies a robust
//   loss to the associated measurements, which absorbs the occasional wrong pair.
// * Confirmation: a landmark started from an unassociated measurement is tentative until it has
//   been associated at least min_observations times and in at least min_detection_ratio of the
//   scans the sensor model expects it in (sum of pD along the poses so far); it is deleted as soon
//   as its detections fall below that fraction of the expected ones.
#pragma once

#include <vector>

#include "reference/ceres/landmark_association.h"
#include "reference/ceres/scan_association_types.h"
#include "src/core/types.h"

namespace phdslam::reference {

/// How the gated pairs of a scan become an assignment.
enum class ScanAssignment {
  kNearestNeighbour,    ///< greedy global nearest neighbour (below)
  kJointCompatibility,  ///< joint compatibility branch and bound (joint_compatibility.h)
};

struct ScanAssociationOptions {
  double gate_chi2 = 13.8;  ///< squared Mahalanobis gate (2 dof; 13.8 = 0.999)
  /// Landmarks farther than this from the pose are skipped before gating (m); <= 0: none
  /// skipped. Set it to the sensor range plus a few gate widths.
  double max_landmark_distance = 0.0;
  /// A gated pair is admissible only when pD N(nu; 0, S) reaches this intensity (per m per
  /// rad); 0: every pair inside the gate is.
  double new_landmark_intensity = 0.0;
  ScanAssignment assignment = ScanAssignment::kNearestNeighbour;
  int jcbb_max_nodes = 20000;  ///< kJointCompatibility: joint tests per scan (>= 1)
  /// kJointCompatibility: 0 takes the most pairs; > 0 the least -log likelihood with this
  /// intensity (per m per rad) for a measurement left out (joint_compatibility.h).
  double jcbb_null_intensity = 0.0;
};

/// Associates one scan with the map. Throws std::invalid_argument when gate_chi2 <= 0,
/// new_landmark_intensity < 0 or jcbb_max_nodes < 1.
ScanAssociation AssociateScan(const Pose& pose, const Mat3& pose_cov,
                              const std::vector<MapLandmark>& map,
                              const std::vector<Measurement>& scan, const Mat2& measurement_cov,
                              const ScanAssociationOptions& options);

/// Rule that confirms and deletes landmarks started from unassociated measurements.
struct ConfirmationOptions {
  int min_observations = 3;
  double min_detection_ratio = 0.3;
};

enum class LandmarkStatus { kTentative, kConfirmed, kDeleted };

/// A landmark's support so far: the scans it was associated in and the detections expected.
struct LandmarkSupport {
  int detections = 0;
  double expected = 0.0;  ///< sum of pD over the scans since its start (its own first included)
};

/// kDeleted when detections < min_detection_ratio * expected; otherwise kConfirmed when
/// detections >= min_observations, else kTentative.
LandmarkStatus ClassifyLandmark(const LandmarkSupport& support, const ConfirmationOptions& options);

/// Landmarks of `association` (steps [first_step, association.size())) that lie closer than
/// `min_range` to a pose they are associated from, in increasing index, each once. The
/// range-bearing model is degenerate there (its Jacobian grows as 1/range, the bearing is
/// undefined on the pose): a solve puts a landmark there when its detections do not belong
/// together, and its column then dwarfs every other in the covariance's rank test.
std::vector<int> CollapsedLandmarks(const Association& association, const std::vector<Pose>& poses,
                                    const std::vector<Landmark>& landmarks, std::size_t first_step,
                                    double min_range);

}  // namespace phdslam::reference
