// The incremental solve (README.md, "Incremental solve"): the graph is built in time order and
// optimised as it grows, so that every linearisation point comes from an optimised past rather
// than from dead reckoning. Every chunk_steps steps the new poses are predicted from the newest
// optimised pose by the odometry, new landmarks are started from those poses, and the newest
// active_steps poses (all when 0) are optimised with the older ones held as they stand.
//
// With the smoother's own association each scan is first associated with the current optimised
// map (scan_association.h), gated on the marginal covariances of the newest optimised pose
// (propagated by the odometry since) and of the landmarks, both from the last chunk's solve and
// conditional on the held poses; landmarks are confirmed by repeated association and deleted when
// they fall below the detection ratio.
#pragma once

#include <ceres/ceres.h>

#include <functional>
#include <vector>

#include "datasets/scenario.h"
#include "reference/ceres/factor_graph.h"
#include "reference/ceres/landmark_association.h"
#include "reference/ceres/multi_scan_relocalisation.h"
#include "reference/ceres/scan_association.h"

namespace phdslam::reference {

struct IncrementalSettings {
  std::size_t chunk_steps = 25;    ///< steps added between two solves (>= 1)
  std::size_t active_steps = 500;  ///< newest poses optimised per solve; 0: all
  /// Measurements of held poses folded into a fixed prior on their landmarks
  /// (held_measurement_prior.h); false: re-evaluated in every chunk solve.
  bool held_prior = true;
  SolveSettings solve;  ///< settings of each chunk's solve
};

/// Called after every chunk solve with its summary and wall time.
using SolveObserver = std::function<void(const ceres::Solver::Summary&, double seconds)>;

/// Known or filter association: the poses and the `landmark_count` landmarks of `association`
/// estimated chunk by chunk. `odometry.increments` give the predictions. `poses` and `landmarks`
/// are resized to one per step and one per landmark (a landmark never observed stays at zero).
void IncrementalSolve(const datasets::Scenario& scenario, const OdometrySpec& odometry,
                      const Association& association, std::size_t landmark_count,
                      ceres::LossFunction* loss, const IncrementalSettings& settings,
                      const SolveObserver& observer, std::vector<Pose>* poses,
                      std::vector<Landmark>* landmarks);

struct IncrementalAssociationOptions {
  ScanAssociationOptions gate;
  ConfirmationOptions confirmation;
  models::SensorModel sensor;               ///< FOV and pD for the expected detections
  Mat2 measurement_cov = Mat2::Identity();  ///< R
  /// Gate marginals from the squared-loss graph at each chunk's solution (false: from the
  /// chunk's robust graph, whose covariance is singular when a landmark's few measurements lie
  /// beyond the loss scale).
  bool squared_loss_marginals = false;
  /// When ceres::Covariance fails on a chunk's graph, the gate's marginals are computed again
  /// without the measurements of the landmarks within one range standard deviation (sqrt R(0,0))
  /// of a free pose they are associated from (README.md, "Collapsed landmarks").
  bool marginals_without_collapsed = true;
  /// Such a landmark is also deleted after every chunk solve, its measurements unassociated.
  bool delete_collapsed = false;
  /// A measurement inside the gates of two or more landmarks is left unassociated and starts no
  /// landmark (README.md, "Ambiguous measurements"). false: nearest neighbour decides.
  bool skip_ambiguous = false;
  /// Only a measurement outside every landmark's gate starts a landmark; one that lost its
  /// nearest landmark to a closer measurement of the scan stays unassociated. false: every
  /// unassociated measurement starts one.
  bool birth_outside_gates = false;
  /// Gate with each landmark's cross-covariance with the pose, Cov(m, x): from the chunk's graph
  /// after each solve, and for a landmark started or refined since then as the pass propagates
  /// it (README.md, "Own association along the incremental solve"). false: C = 0.
  bool pose_landmark_cross = false;
  /// Static-point check (static_point_check.h, README.md "Moving objects"): each detection
  /// associated with a landmark is compared with the landmark's first detection through the
  /// odometry between them; above this chi-square (2 dof) the landmark is deleted as a moving
  /// object (its measurements unassociated) and the detection starts a new landmark. 0: off.
  double static_point_chi2 = 0.0;
  /// The first-detection anchor moves to the latest detection once the odometry since it has a
  /// heading standard deviation above this (rad).
  double static_point_heading_std = 0.2;
  /// Consecutive detections that must fail against the first detection while agreeing with
  /// the latest before the landmark is deleted (1: the first such detection).
  int static_point_failures = 1;
  /// The odometry increments with the model's own floor (not the warm-start floor), one per
  /// step, for that test; required when it is on.
  const std::vector<OdometryIncrement>* model_increments = nullptr;
  /// Re-localisation with evidence (multi_scan_relocalisation.h, README.md "Re-localisation
  /// after dead reckoning"): once the pose's marginal position standard deviation (the larger
  /// axis) exceeds this (m), the landmarks mapped so far are no longer gated scan by scan; the
  /// detections of the last relocalisation_scans scans with detections are matched with them
  /// together, and only a unique match associates them with those landmarks (and corrects the
  /// poses and the landmarks started since the threshold was crossed). Meanwhile detections
  /// are associated with, or start, new landmarks only. 0: off.
  double relocalisation_position_std = 0.0;
  int relocalisation_scans = 5;  ///< scans with detections matched together (>= 2)
  RelocalisationOptions relocalisation;
  /// When the match is ambiguous (a rival within the margin of a best with three or more
  /// inliers: the map admits several corrections), leave the mode without a correction and
  /// gate scan by scan again. false: keep matching at every further scan.
  bool relocalisation_leave_ambiguous = false;
};

/// Own association: scan-to-map association, confirmation and deletion along the incremental
/// solve (robust `loss` in every chunk solve). Returns the confirmed landmarks (renumbered
/// 0..n-1 in order of creation) with the association and the poses of the last chunk solve.
/// `association_seconds` accumulates the time spent outside the solves; `collapsed`, when given,
/// counts the landmarks deleted as collapsed onto a pose.
AssociatedMap IncrementalAssociation(const datasets::Scenario& scenario,
                                     const OdometrySpec& odometry, ceres::LossFunction* loss,
                                     const IncrementalSettings& settings,
                                     const IncrementalAssociationOptions& options,
                                     const SolveObserver& observer, double* association_seconds,
                                     int* collapsed = nullptr);

}  // namespace phdslam::reference
