// Ceres batch smoother: full-trajectory graph optimisation (no GTSAM) over every pose of a
// scenario and the landmarks, the reference the filters are compared with. See README.md for the
// factors, the gauge, the solver choice and the association modes.
//
//   pose_k --OdometryFactor-- pose_{k+1}        (one per step with propagation)
//   pose_k --RangeBearingFactor-- landmark_i    (one per associated measurement)
//   pose_0 fixed (or an odometry factor from the fixed initial pose when step 0 propagates)
#pragma once

#include <string>
#include <vector>

#include "datasets/batch_estimator.h"
#include "datasets/scenario.h"
#include "reference/ceres/association_posterior.h"
#include "reference/ceres/factor_graph.h"
#include "reference/ceres/landmark_association.h"
#include "reference/ceres/odometry_increment.h"
#include "reference/ceres/scan_association.h"
#include "src/filters/estimator.h"

namespace phdslam::reference {

enum class AssociationMode {
  kKnown,    ///< the generator's labels scenario.steps[k].origin (hidden data: oracle-like)
  kFilter,   ///< a filter's association, SmootherOptions::filter_association
  kUnknown,  ///< the smoother's own association (README.md, "Unknown association")
};

/// Where the linearisation points of the final solve come from (README.md, "Incremental solve").
enum class SmootherInitialisation {
  /// The graph is built in time order and solved as it grows (chunks of incremental_chunk_steps
  /// steps, the newest incremental_active_steps poses optimised); the own association associates
  /// each scan with the optimised map. Ignored when initial_poses is given.
  kIncremental,
  /// The whole graph from dead reckoning (or initial_poses); the own association from the
  /// sequential EKF pass with a solve every initial_pass_solve_steps steps.
  kBatch,
};

/// The trajectory the registry starts the smoother from (README.md, "Start from another
/// estimator's trajectory").
enum class StartTrajectory {
  kDeadReckoning,  ///< initial_poses left empty: dead reckoning (or the incremental solve)
  kPhd3,           ///< a PHD-SLAM 3.0 run on the same data and stream fills initial_poses
  /// the fixed-lag smoother's own-association run (`window`, its defaults on the scenario) on
  /// the same data fills initial_poses: a graph-SLAM front end that starts from dead reckoning
  kWindow,
};

/// The online estimator whose association smoother-filter solves (the registry builds it).
enum class FilterFrontEnd {
  kPhd3,    ///< a PHD-SLAM 3.0 run (N = 1), its associated means linked by filter_label_distance
  kWindow,  ///< the fixed-lag smoother's own association (`window`), its labels as they are
};

/// Stage 1 of the own association (smoother-unknown): where its first association comes from.
enum class OwnFrontEnd {
  /// the sequential pass (batch) or the scan-to-map association of the incremental solve
  kPass,
  /// the fixed-lag smoother's own association (`window`, its defaults on the scenario): its
  /// labels and trajectory, given as filter_association and initial_poses (the registry runs it
  /// through FilterThenSmooth), then the re-association rounds and the final squared-loss solve
  kWindow,
};

/// Which trajectory of the start_from filter run fills initial_poses (README.md, "Start from
/// another estimator's trajectory").
enum class StartPath {
  kEstimate,          ///< the filter's estimate of every step (its highest-weight particle then)
  kBestParticlePath,  ///< the path of the highest-weight particle of the last step
};

/// How the odometry factor is whitened (README.md, "Odometry factor").
enum class OdometryResidual {
  /// Velocity-model steps with one sub-interval: the control that explains the relative pose,
  /// whitened by Qu, plus the no-sideways-slip constraint (VelocityOdometryFactor); other steps
  /// (car model, several sub-intervals) fall back to kPoseSpace.
  kControlSpace,
  /// Every step: the pose increment whitened by the propagated covariance plus the floor
  /// (OdometryFactor).
  kPoseSpace,
};

struct SmootherOptions {
  AssociationMode association = AssociationMode::kKnown;
  SmootherInitialisation initialisation = SmootherInitialisation::kBatch;
  /// Incremental solve: steps added between two solves.
  int incremental_chunk_steps = 25;
  /// Incremental solve: the newest poses optimised in each chunk's solve, older ones held as they
  /// stand (0: every pose). The final solve always optimises every pose.
  int incremental_active_steps = 500;
  /// Incremental solve: the measurements taken from held poses are folded, once, into a fixed
  /// Gaussian prior on their landmarks (held_measurement_prior.h), so that a chunk solve costs
  /// the same at every chunk; false re-evaluates them in every chunk solve.
  bool incremental_held_prior = true;
  /// Incremental solve, own association: the gate's marginal covariances from the squared-loss
  /// graph at each chunk's solution instead of the robust one (README.md, "Own association along
  /// the incremental solve").
  bool incremental_squared_marginals = false;
  /// Incremental solve, own association: when the gate's marginal covariances fail, they are
  /// computed again without the landmarks collapsed onto a pose (within one range standard
  /// deviation of a pose they are associated from; README.md, "Collapsed landmarks").
  bool incremental_marginals_without_collapsed = true;
  /// Incremental solve, own association: such a landmark is also deleted after every chunk solve.
  bool incremental_delete_collapsed = false;
  /// Incremental solve, own association: a measurement inside the gates of two or more
  /// landmarks is left unassociated and starts none (README.md, "Ambiguous measurements").
  bool incremental_skip_ambiguous = false;
  /// Incremental solve, own association: only measurements outside every gate start landmarks.
  bool incremental_birth_outside_gates = false;
  /// Incremental solve, own association: the gate uses each landmark's cross-covariance with the
  /// pose (README.md, "Own association along the incremental solve"); false leaves it out.
  bool incremental_pose_landmark_cross = false;
  /// Incremental solve, own association: a pair inside the gate is admissible only when
  /// pD N(nu; 0, S) reaches this intensity (per m per rad of range-bearing space), the
  /// likelihood of a new landmark or clutter; 0 turns the test off.
  double incremental_new_landmark_intensity = 0.0;
  /// Incremental solve, own association: each scan's gated pairs by greedy nearest neighbour or
  /// by joint compatibility branch and bound against the chunk solution's marginals
  /// (joint_compatibility.h).
  ScanAssignment incremental_assignment = ScanAssignment::kNearestNeighbour;
  int incremental_jcbb_max_nodes = 20000;  ///< joint compatibility tests per scan (>= 1)
  /// jcbb: 0 takes the most jointly compatible pairs; > 0 the assignment of the highest
  /// likelihood, each measurement left out weighed by this intensity (per m per rad).
  double incremental_jcbb_null_intensity = 0.0;
  /// Incremental solve, own association: a landmark whose detection, carried to its first one by
  /// the odometry between them, is farther from it than this chi-square (2 dof) is deleted as a
  /// moving object (README.md, "Moving objects"); 0 turns the test off.
  double incremental_static_point_chi2 = 0.0;
  /// The static-point check compares a detection with the landmark's first one only while the
  /// odometry between them has a heading standard deviation below this (rad); beyond it the
  /// anchor moves to the latest detection. Over long stretches of dead reckoning the carried
  /// point's first-order covariance understates its spread (README.md, "Moving objects").
  double incremental_static_point_heading_std = 0.2;
  /// Consecutive detections that must move (fail against the first detection, agree with the
  /// latest) before the static-point check deletes the landmark; 1: the first one.
  int incremental_static_point_failures = 1;
  /// Incremental solve, own association: while the pose's marginal position standard deviation
  /// exceeds this (m), the detections of the next incremental_relocalisation_scans scans are
  /// matched with the map together and associated only on a unique match (README.md,
  /// "Re-localisation after dead reckoning"); until then they are unassociated. 0: off.
  double incremental_relocalisation_std = 0.0;
  int incremental_relocalisation_scans = 5;  ///< scans with detections matched together (>= 2)
  /// A detection within this of a landmark after the candidate correction is an inlier (m).
  double incremental_relocalisation_inlier_distance = 0.5;
  /// Inliers by which the best correction must beat every rival.
  int incremental_relocalisation_margin = 2;
  /// A correction scores its inliers less this times half the squared Mahalanobis distance of
  /// the pose it implies from the dead-reckoned one; 0: the inliers alone.
  double incremental_relocalisation_prior_weight = 0.0;
  /// An ambiguous match (a rival within the margin) ends the re-localisation without a
  /// correction, and association goes on scan by scan; false: keep matching.
  bool incremental_relocalisation_leave_ambiguous = false;
  /// Known association: a labelled measurement whose squared whitened residual (chi-square, 2
  /// dof) at the warm-started estimate exceeds this is left out of the final solves as a
  /// mislabelled detection (README.md, "Outliers in the known association"); the incremental
  /// chunk solves then use the robust loss. 1000 (31.6 sigma) leaves out only gross outliers:
  /// UTIAS MRCLAM's misread barcodes are at ~5e4, the genuine detections below 1000. 0 uses every
  /// labelled measurement with the squared loss throughout (the reference behaviour).
  double known_outlier_chi2 = 1000.0;
  int max_iterations = 100;          ///< Levenberg-Marquardt iterations per solve
  double function_tolerance = 1e-9;  ///< relative cost decrease that ends the final solve
  /// Ends the solves before the final one (warm start, association), which only need to bring
  /// the estimate close.
  double intermediate_function_tolerance = 1e-6;
  bool compute_covariances = true;  ///< marginal pose and landmark covariances (ceres::Covariance)
  SparseLinearSolver linear_solver = SparseLinearSolver::kSparseNormalCholesky;
  int num_threads = 1;
  OdometryResidual odometry_residual = OdometryResidual::kControlSpace;
  /// Pose-space floor (odometry_increment.h); in control space, position_std is the std of the
  /// no-sideways-slip constraint.
  OdometryNoiseFloor odometry_floor;
  /// A looser floor for every solve but the last (README.md, "Odometry floor"): from dead
  /// reckoning, a tight floor makes the odometry a near-rigid chain and Levenberg-Marquardt
  /// crawls; a first solve with this floor brings the trajectory close, and the final solve with
  /// odometry_floor then takes a few iterations. No effect when not larger than odometry_floor.
  OdometryNoiseFloor warm_start_floor{0.05, 1e-5};

  // Unknown mode (README.md): solve with a robust loss, re-associate, repeat; then a final solve
  // with the squared loss on the last (gated) association.
  /// Batch initialisation: the initial sequential association pass is interrupted every this many
  /// steps by a solve of the steps done so far, and continues from the smoothed trajectory and map
  /// (0: never).
  int initial_pass_solve_steps = 200;
  int reassociation_rounds = 5;  ///< maximum solve/re-associate rounds
  /// Gate for associating a measurement and for merging landmarks: chi2 with 2 dof at 0.999.
  double gate_chi2 = 13.8;
  /// Landmarks (created from unassociated measurements, or filter-mode labels) seen fewer times
  /// are dropped. 3 keeps
  /// every real landmark of the synthetic scenario (hundreds of detections each) and removes
  /// almost all clutter, which lands twice in the same gate with probability ~1e-3 per point.
  int min_observations = 3;
  /// Merging adds this std to both landmarks' covariances (relative drift between two visits).
  double merge_position_std = 1.0;
  /// Landmarks detected in fewer than this fraction of the scans the sensor model expects them
  /// in (sum of pD along the trajectory) are dropped: real landmarks score about 1, clutter that
  /// fell into one gate a few times scores ~0.01-0.1.
  double min_detection_ratio = 0.3;
  /// "cauchy", "huber" or "none"; the scale is in whitened units (standard deviations).
  std::string robust_loss = "cauchy";
  double robust_scale = 1.0;

  /// Initial trajectory, one pose per step; empty: dead reckoning. The known and filter modes
  /// start their solves from it; the unknown mode's sequential pass follows its relative motion
  /// instead of the odometry (start_trajectory.h) and makes its own association from there.
  std::vector<Pose> initial_poses;
  /// Where the registry's smoother-known and smoother-unknown get initial_poses from (README.md,
  /// "Start from another estimator's trajectory"); BatchSmoother itself reads only initial_poses.
  StartTrajectory start_from = StartTrajectory::kDeadReckoning;
  /// Particles of the PHD-SLAM 3.0 run of start_from = kPhd3.
  int start_particles = 5;
  /// Which trajectory of that run: its per-step estimates or its best final particle's path
  /// (particle_lineage.h). Only with start_from = kPhd3.
  StartPath start_path = StartPath::kEstimate;

  // Filter mode: per step, per measurement, the landmark id of a filter's association (any
  // non-negative label; -1 = clutter). Labels with fewer than min_observations detections are
  // treated as clutter; the rest is solved as given, with the robust loss above.
  std::vector<std::vector<int>> filter_association;
  /// FilterThenSmooth (filter_association.h): associated landmark means of consecutive scans
  /// closer than this (m) are the same landmark.
  double filter_label_distance = 2.0;
  FilterFrontEnd filter_front_end = FilterFrontEnd::kPhd3;
  /// Own association: stage 1 from its own pass or from the window's labels (filter_association,
  /// which the unknown mode then requires).
  OwnFrontEnd front_end = OwnFrontEnd::kPass;

  /// How the final solution is scored (association_posterior.h): the Poisson birth term per
  /// landmark by default, the flat map prior of earlier versions as posterior_map_prior = flat.
  PosteriorOptions posterior;

  /// Throws std::invalid_argument naming the field when an option is out of range.
  void Validate() const;
};

/// What a Solve did, for logs and reports.
struct SmootherReport {
  int iterations = 0;  ///< Levenberg-Marquardt iterations summed over all solves
  int solves = 0;
  int reassociation_rounds = 0;        ///< rounds run (unknown mode)
  bool association_converged = false;  ///< the last round left the association unchanged
  double association_seconds = 0.0;
  double optimisation_seconds = 0.0;
  double covariance_seconds = 0.0;
  bool covariance_ok = false;
  std::size_t landmarks = 0;
  std::size_t associated_measurements = 0;
  int outliers_dropped = 0;  ///< known association: measurements left out (known_outlier_chi2)
  int moving_landmarks = 0;  ///< own association: landmarks deleted by the static-point check
  int relocalisations = 0;   ///< own association: re-localisations applied
  int relocalisations_abandoned = 0;  ///< own association: re-localisations left as ambiguous
  int unconverged_solves = 0;         ///< solves stopped by the iteration limit or a failure
  /// The final solve met a tolerance (ceres CONVERGENCE); false when it stopped at
  /// max_iterations or failed, and its estimate is then reported as not converged.
  bool converged = false;
  double initial_cost = 0.0;  ///< of the last solve
  double final_cost = 0.0;    ///< of the last solve
  /// The final solution's negative log posterior (association_posterior.h), by term.
  PosteriorTerms posterior;
  std::vector<std::string> brief_reports;  ///< ceres::Solver::Summary::BriefReport per solve
};

class BatchSmoother final : public datasets::BatchEstimator {
 public:
  /// Throws std::invalid_argument naming the field when an option is out of range.
  explicit BatchSmoother(SmootherOptions options);

  /// Known mode reads scenario.steps[k].origin (throws std::invalid_argument when a step's labels
  /// do not match its measurements); filter mode reads options.filter_association (same check);
  /// unknown mode reads only the public part. BatchResult.solve_seconds is the wall time of the
  /// whole call, covariances included. map.log_weights are 0. When compute_covariances is off,
  /// pose_covs are empty optionals and map.covs hold the pose-known approximation
  /// (sum Hm^T R^-1 Hm)^-1.
  datasets::BatchResult Solve(const datasets::Scenario& scenario) override;

  /// After Solve: per step, per measurement, the index into BatchResult.map (kUnassociated for
  /// clutter or unused measurements).
  [[nodiscard]] const Association& association() const { return association_; }
  /// After Solve: for each map entry its source label (truth landmark index in known mode, the
  /// filter's id in filter mode, creation order in unknown mode).
  [[nodiscard]] const std::vector<int>& landmark_labels() const { return labels_; }
  [[nodiscard]] const SmootherReport& report() const { return report_; }
  [[nodiscard]] const SmootherOptions& options() const { return options_; }

 private:
  SmootherOptions options_;
  Association association_;
  std::vector<int> labels_;
  SmootherReport report_;
};

/// The odometry increments of every step of `scenario` (shared by the smoother and the g2o export).
std::vector<OdometryIncrement> ScenarioOdometry(const datasets::Scenario& scenario,
                                                const OdometryNoiseFloor& floor);

/// Dead reckoning with the increments: pose k = pose_{k-1} (+) delta_k from the initial pose.
std::vector<Pose> DeadReckoning(const datasets::Scenario& scenario,
                                const std::vector<OdometryIncrement>& increments);

}  // namespace phdslam::reference
