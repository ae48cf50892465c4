// Fixed-lag (sliding-window) smoother: the online graph-optimisation baseline (README.md,
// "Fixed-lag smoother"). It keeps the newest `window_length` poses and the landmarks they see in
// a Ceres problem, solves it every `solve_every` steps (Levenberg-Marquardt warm-started from the
// previous solution and the odometry prediction), and marginalises the oldest pose, with the
// landmarks no later pose sees, into a Gaussian prior (marginalization.h): the Schur complement
// of the linearised problem, kept as a whitened linear residual whose linearisation points stay
// fixed (first-estimate Jacobians, linear_prior.h). A landmark leaves with its mean and marginal
// covariance; when it is seen again it re-enters the window with that Gaussian as its prior.
//
// The pose of each step is the newest window pose after that step (a filtered estimate, not a
// smoothed one); the map is every landmark in the window plus every marginalised one.
#pragma once

#include <cstddef>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "reference/ceres/association_labels.h"
#include "reference/ceres/batch_smoother.h"
#include "reference/ceres/marginalization.h"
#include "reference/ceres/odometry_increment.h"
#include "reference/ceres/scan_association.h"
#include "reference/ceres/static_point_check.h"
#include "src/filters/estimator.h"
#include "src/filters/solve_counter.h"

namespace phdslam::reference {

struct WindowParams {
  /// Known: the generator's labels (fixed by the estimator's name, window-known); unknown: the
  /// smoother's own association (window_association.h).
  bool known_association = true;
  /// Poses kept in the window after each solve (>= 1, at most the run's length).
  int window_length = 20;
  int solve_every = 1;  ///< steps between solves (>= 1); the window holds up to
                        ///< window_length + solve_every - 1 poses before a solve
  /// A landmark no window pose observes stays in the window, held by the marginal prior with its
  /// correlations, until it has gone unobserved for this many steps; it is then marginalised.
  /// 0: marginalised as soon as no window pose observes it.
  int landmark_keep_steps = 0;
  int max_iterations = 10;           ///< Levenberg-Marquardt iterations per solve
  double function_tolerance = 1e-6;  ///< relative cost decrease that ends a solve
  OdometryResidual odometry_residual = OdometryResidual::kControlSpace;
  OdometryNoiseFloor odometry_floor;  ///< as the batch smoother's (odometry_increment.h)
  // Own association (window, docs/algorithms/ceres-smoother.md section 8.3): gated nearest
  // neighbour, confirmed landmarks first; confirmation and deletion of tentative ones.
  double gate_chi2 = 13.8;  ///< chi2 with 2 dof at 0.999 on the marginal innovation covariance
  /// The assignment of each scan's gated pairs: greedy nearest neighbour or joint compatibility
  /// branch and bound over the scan (joint_compatibility.h), both against confirmed landmarks
  /// first, then the rest against tentative ones.
  ScanAssignment assignment = ScanAssignment::kNearestNeighbour;
  int jcbb_max_nodes = 20000;  ///< joint compatibility tests per scan and landmark set (>= 1)
  /// jcbb: 0 takes the most jointly compatible pairs; > 0 the most likely assignment, a
  /// measurement left out weighed by this intensity (per m per rad).
  double jcbb_null_intensity = 0.0;
  /// A tentative landmark is confirmed once this many scans have associated with it (its first
  /// detection included) ...
  int confirm_detections = 5;
  /// ... and deleted as soon as its detections fall below this fraction of the scans expected to
  /// detect it since its first detection (the sum of pD at the predicted pose of each of them).
  /// One still tentative when the pose of its first detection leaves the window is deleted too.
  double confirm_ratio = 0.5;
  /// Loss on the detections of confirmed landmarks: "huber", "cauchy" or "none"
  std::string robust_loss = "huber";
  double robust_scale = 3.0;  ///< in whitened units (standard deviations)
  /// Cauchy loss scale on the detections of tentative landmarks (whitened units)
  double tentative_robust_scale = 1.0;
  /// After each solve, drop the detections of confirmed landmarks outside the gate and solve again
  bool reject_outliers = true;
  /// Moving-object test (static_point_check.h, README.md "Moving objects"): a detection
  /// associated with a landmark is compared with the landmark's first detection, carried by the
  /// odometry alone; beyond this chi-square (2 dof) while agreeing with the latest detection it
  /// "moves", and the landmark is a moving object after static_point_failures such detections
  /// in a row. Its detections then count as clutter: it is deleted, or, when the marginal prior
  /// already holds it, left out of the association and the map; it becomes a moving track, and
  /// a detection that would start a landmark within this chi-square of the track's latest
  /// detection is the object's (clutter) until the track goes unseen for window_length steps,
  /// or until confirm_detections such detections in a row stay within it of the first of them
  /// (the object stands still, or a static landmark was taken for it): the next one starts a
  /// landmark. 0: off.
  double static_point_chi2 = 0.0;
  /// The first detection gives way to the latest once the odometry's heading std since exceeds
  /// this (rad).
  double static_point_heading_std = 0.2;
  int static_point_failures = 1;  ///< consecutive moving detections that make a moving object

  /// Throws std::invalid_argument naming the field when a value is out of range; `run_steps`
  /// (> 0 when known) bounds window_length.
  void Validate(std::size_t run_steps = 0) const;
};

/// What the smoother did, over the whole run.
struct WindowReport {
  int solves = 0;
  int unconverged_solves = 0;  ///< NO_CONVERGENCE (kept) or FAILURE (discarded): see README.md
  int iterations = 0;
  int marginalised_poses = 0;
  int deleted_landmarks = 0;    ///< own association: tentative landmarks never confirmed
  int rejected_detections = 0;  ///< own association: detections dropped after a solve
  int moving_landmarks = 0;     ///< own association: landmarks found moving (static_point_chi2)
};

class FixedLagSmoother final : public filters::OnlineEstimator,
                               public filters::SolveCounter,
                               public LabelledAssociation {
 public:
  /// `origins`: per step, per measurement, the landmark label (>= 0) or a negative value
  /// (clutter, unknown); required (one entry per step) with known_association, ignored
  /// otherwise. `run_steps` bounds window_length (0: unknown). Throws std::invalid_argument
  /// naming the parameter.
  FixedLagSmoother(filters::EstimatorContext context, WindowParams params,
                   std::vector<std::vector<int>> origins = {}, std::size_t run_steps = 0);

  filters::StepOutput Step(const StepData& step) override;
  [[nodiscard]] filters::MapEstimate Map() const override;

  /// Every pose currently in the window, oldest first (tests: the window of a whole run is the
  /// batch solution).
  [[nodiscard]] std::vector<Pose> WindowPoses() const;
  [[nodiscard]] const WindowReport& report() const { return report_; }
  /// Own association: each detection's landmark label as the run ended (confirmed landmarks
  /// only; -1 for clutter, deleted or moving landmarks and rejected detections). Known
  /// association: the labels used.
  [[nodiscard]] std::vector<std::vector<int>> FinalLabels() const override;
  [[nodiscard]] filters::SolveCounts Solves() const override {
    return {report_.solves, report_.unconverged_solves};
  }

 private:
  struct Observation {
    int landmark;
    std::size_t measurement;
    GraphFactor factor;
  };
  struct WindowPose {
    std::size_t step = 0;
    Pose x = Pose::Zero();
    bool constant = false;
    std::optional<GraphFactor> odometry;  ///< from the previous pose or the anchor
    std::vector<Observation> observations;
  };
  struct WindowLandmark {
    Landmark mean = Landmark::Zero();
    Mat2 cov = Mat2::Identity();  ///< marginal covariance when marginalised
    bool active = true;           ///< in the window (false: marginalised)
    LandmarkSupport support;      ///< detections and sum of pD over the scans since the first one
    LandmarkStatus status = LandmarkStatus::kTentative;
    std::size_t first_step = 0;
    std::size_t last_step = 0;                 ///< step of its latest detection
    std::optional<GraphFactor> reentry_prior;  ///< N(mean, cov) when it came back into the window
    StaticPointTrack static_point;  ///< first and latest detection, odometry since (moving test)
    bool moving = false;  ///< found moving while held by the prior: out of association and map
  };
  /// A moving object's latest detection, carried by the odometry (static_point_chi2).
  struct MovingTrack {
    StaticPointAnchor latest;
    std::optional<StaticPointAnchor> first;  ///< first detection taken since the last check
    int taken = 0;                           ///< detections taken since the last check
    std::size_t last_step = 0;
  };

  void AddPose(const StepData& step);
  void AddObservations(const StepData& step, filters::StepOutput& out);
  void Observe(WindowPose& pose, int label, std::size_t j, const Measurement& z);
  std::vector<int> OwnAssociation(const StepData& step);
  void CountExpectedDetections(const Pose& x);
  /// Moving-object test on the scan's associations (static_point_chi2 > 0): a label whose
  /// landmark is found moving becomes clutter (-1).
  void DropMovingObjects(const StepData& step, std::vector<int>& labels);
  /// Whether z, which would start a landmark, continues a moving track (and updates it).
  bool ContinuesMovingTrack(const Measurement& z);
  void AdvanceStaticPointTracks(const OdometryIncrement& increment);
  [[nodiscard]] bool HeldByPrior(const WindowLandmark& lm) const;
  void ClassifyTentative();
  void Solve();
  /// Own association: drops the detections of confirmed landmarks whose whitened residual at the
  /// solved window lies outside the gate (squared norm >= gate_chi2); returns how many.
  int RejectOutliers();
  void MarginaliseOldest();
  void DeleteLandmark(int label);
  [[nodiscard]] std::vector<const GraphFactor*> WindowFactors() const;
  [[nodiscard]] std::set<const double*> ConstantBlocks() const;
  /// Whether the landmark has gone unobserved for landmark_keep_steps (true when it is 0).
  [[nodiscard]] bool KeepTimeOver(const WindowLandmark& lm) const;
  [[nodiscard]] bool ObservedAfterOldest(int label) const;

  filters::EstimatorContext context_;
  WindowParams params_;
  std::vector<std::vector<int>> origins_;
  bool velocity_model_ = false;
  std::shared_ptr<ceres::LossFunction> loss_;
  std::shared_ptr<ceres::LossFunction> tentative_loss_;
  Mat2 measurement_whitening_ = Mat2::Identity();

  std::size_t step_index_ = 0;
  Pose anchor_ = Pose::Zero();
  std::deque<WindowPose> poses_;
  std::map<int, WindowLandmark> landmarks_;
  int next_label_ = 0;  ///< own association: label of the next new landmark
  std::vector<MovingTrack> moving_tracks_;
  std::vector<std::vector<int>> label_log_;  ///< per step, per measurement: the label observed
  std::optional<GraphFactor> prior_;
  FixedPoints fixed_points_;
  int steps_since_solve_ = 0;
  WindowReport report_;
};

}  // namespace phdslam::reference
