// Data association for the smoother's unknown-association mode (README.md, "Unknown
// association"). Two stages share one gating rule and one per-step assignment:
//
// * Gating: measurement z at pose x against landmark (m, P): innovation
//   nu = [z_r - h_r; wrap(z_phi - h_phi)], S = Hx Px Hx^T + Hm P Hm^T + R, accepted when
//   nu^T S^-1 nu < gate_chi2 (strict).
// * Assignment within a step: candidate pairs in increasing Mahalanobis distance, each
//   measurement and each landmark used at most once (greedy global nearest neighbour).
//
// SequentialAssociation is the initial pass: it walks the steps in order like a single-particle
// filter, tracking the pose with an iterated EKF on the landmarks confirmed so far, refining the
// landmarks with pose-known EKF updates and creating a landmark for every unassociated
// measurement. Reassociate re-does the association at a solved trajectory and map.
//
// Both stages end by dropping landmarks with too little support: fewer than min_observations
// detections, or fewer than min_detection_ratio times the detections the sensor model expects
// at the landmark from the trajectory. Clutter falls into a common gate a few times by chance
// (often on later passes over the same place) but is detected in only a small fraction of the
// scans whose FOV covers it; a real landmark in about pD of them.
#pragma once

#include <memory>
#include <vector>

#include "datasets/scenario.h"
#include "reference/ceres/odometry_increment.h"
#include "src/core/types.h"
#include "src/models/sensor_model.h"

namespace phdslam::reference {

/// Per step, per measurement: the landmark index, or kUnassociated.
using Association = std::vector<std::vector<int>>;
inline constexpr int kUnassociated = -1;

struct AssociationOptions {
  double gate_chi2 = 13.8;   ///< squared Mahalanobis gate (2 dof)
  int min_observations = 3;  ///< landmarks seen fewer times are dropped (and, in the initial
                             ///< pass, do not correct the pose)
  /// Merging adds merge_position_std^2 I to the two landmarks' covariances: the relative drift of
  /// the trajectory between two visits, which the pose-known landmark covariances leave out.
  double merge_position_std = 1.0;  ///< m
  /// Landmarks detected fewer than min_detection_ratio times the number of detections the sensor
  /// model predicts for them (sum over steps of pD(x_k, m), FOV included) are dropped too.
  double min_detection_ratio = 0.3;
  models::SensorModel sensor;               ///< FOV and pD for the expected detections
  Mat2 measurement_cov = Mat2::Identity();  ///< R (normally sensor.noise_cov)
  /// Per step and measurement, those Reassociate leaves unassociated and starts nothing from (the
  /// detections of moving objects found by the incremental pass); null: none.
  const std::vector<std::vector<bool>>* excluded = nullptr;
};

/// A map with its association: landmarks[i] is referenced by association entries equal to i.
struct AssociatedMap {
  Association association;
  std::vector<Landmark> landmarks;
  std::vector<Pose> poses;            ///< the poses the association was made at
  int merged = 0;                     ///< landmarks merged into another one
  int dropped = 0;                    ///< landmarks dropped for too few observations
  int born = 0;                       ///< landmarks created from unassociated measurements
  int moving = 0;                     ///< landmarks deleted as moving objects (static-point check)
  int relocalisations = 0;            ///< re-localisations applied (incremental pass)
  int relocalisations_abandoned = 0;  ///< re-localisation modes left on an ambiguous match
  /// Per step and measurement: a detection of a landmark deleted as a moving object (empty when
  /// the pass does not check).
  std::vector<std::vector<bool>> excluded;
};

/// The initial pass (stage 1), resumable: the smoother alternates AdvanceTo with a solve of the
/// steps associated so far and Correct, so that the pass continues from a smoothed trajectory
/// and map (README.md, "Unknown association"). `increments[k]` is the odometry of step k; the
/// pass starts at the scenario's initial pose, which is known exactly. `scenario` must outlive
/// the associator.
class SequentialAssociator {
 public:
  SequentialAssociator(const datasets::Scenario& scenario,
                       std::vector<OdometryIncrement> increments, AssociationOptions options);
  ~SequentialAssociator();
  SequentialAssociator(const SequentialAssociator&) = delete;
  SequentialAssociator& operator=(const SequentialAssociator&) = delete;

  /// Associates steps [steps_done(), end) (end is clamped to the number of steps).
  void AdvanceTo(std::size_t end);
  [[nodiscard]] std::size_t steps_done() const;
  /// The steps done so far with only the confirmed landmarks (seen >= min_observations times),
  /// numbered 0..n-1; `track_ids` receives their internal ids for Correct.
  AssociatedMap Confirmed(std::vector<int>* track_ids) const;
  /// Replaces the poses of the steps done and the means of the landmarks `track_ids` by
  /// smoothed values; the next step is predicted from the last of these poses.
  void Correct(const std::vector<Pose>& poses, const std::vector<int>& track_ids,
               const std::vector<Landmark>& means);
  /// Drops the landmarks without support and returns the map of the steps done.
  [[nodiscard]] AssociatedMap Finish() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// The initial pass over all steps without intermediate smoothing.
AssociatedMap SequentialAssociation(const datasets::Scenario& scenario,
                                    const std::vector<OdometryIncrement>& increments,
                                    const AssociationOptions& options);

/// Re-association (stage 3) at the solved `poses` and `landmarks` whose previous association is
/// `previous`: every measurement is gated against every landmark (landmark covariance: the
/// pose-known information of its previous observations); unassociated measurements create new
/// landmarks; landmarks without support are dropped (see above); landmarks within the gate of
/// each other that were (almost) never seen at the same step are merged.
AssociatedMap Reassociate(const datasets::Scenario& scenario, const std::vector<Pose>& poses,
                          const std::vector<Landmark>& landmarks, const Association& previous,
                          const AssociationOptions& options);

/// For each landmark, whether it has support along `poses`: at least min_observations
/// detections and at least min_detection_ratio times sum_k pD(poses[k], landmark).
std::vector<bool> SupportedLandmarks(const Association& association,
                                     const std::vector<Landmark>& landmarks,
                                     const std::vector<Pose>& poses,
                                     const AssociationOptions& options);

/// Number of measurements associated with each of `landmark_count` landmarks.
std::vector<int> CountObservations(const Association& association, std::size_t landmark_count);

}  // namespace phdslam::reference
