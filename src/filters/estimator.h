// The estimator interface shared by the system under test, the oracle and the baselines.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/types.h"
#include "src/models/motion_model.h"
#include "src/models/sensor_model.h"

namespace phdslam::filters {

/// What an estimator may know about a scenario: its public part only.
struct EstimatorContext {
  Pose initial_pose = Pose::Zero();
  std::shared_ptr<const models::MotionModel> motion;
  Mat2 control_noise_cov = Mat2::Identity();
  models::SensorModel sensor;

  static EstimatorContext FromScenario(const datasets::Scenario& s);
};

/// Diagnostics of one step, kept in the run record.
struct StepDiagnostics {
  double ess = 1.0;          ///< effective sample size after the update (before resampling)
  bool resampled = false;
  int hypotheses = 0;        ///< components of the importance density (mean over particles)
  int map_components = 0;    ///< GM-PHD components (active + passive) of the best particle
};

struct StepOutput {
  Pose pose = Pose::Zero();
  std::optional<Mat3> pose_cov;  ///< set by estimators that carry a pose covariance
  StepDiagnostics diag;
  /// Data association of the estimate, for association-accuracy metrics: for each measurement
  /// of the step, the mean of the map landmark it was associated with, or NaN for
  /// "clutter / new landmark". Empty when the estimator does not associate.
  std::vector<Landmark> association;
};

/// A map estimate: landmark means with covariances and log-weights (0 when not meaningful).
struct MapEstimate {
  std::vector<Landmark> means;
  std::vector<Mat2> covs;
  std::vector<double> log_weights;
  [[nodiscard]] std::size_t size() const { return means.size(); }
};

class OnlineEstimator {
 public:
  virtual ~OnlineEstimator() = default;
  /// Processes one filter step and returns the pose estimate at its last time stamp.
  virtual StepOutput Step(const datasets::StepData& step) = 0;
  /// The current map estimate.
  [[nodiscard]] virtual MapEstimate Map() const = 0;
  /// Pose and log-weight of every particle after the last step, for particle filters that
  /// expose them (particle traces); empty otherwise.
  [[nodiscard]] virtual std::vector<std::pair<Pose, double>> ParticleStates() const { return {}; }
};

}  // namespace phdslam::filters

namespace phdslam::filters {

/// Result of a batch (whole-scenario) estimator such as the smoother.
struct BatchResult {
  std::vector<Pose> poses;                 ///< one per step
  std::vector<std::optional<Mat3>> pose_covs;  ///< marginal covariances where computed
  MapEstimate map;
  int iterations = 0;
  double solve_seconds = 0.0;
};

}  // namespace phdslam::filters

namespace phdslam::filters {

/// A batch estimator consumes the whole scenario at once. It receives the full Scenario; an
/// implementation documents which hidden parts (origin labels) a mode reads, if any.
class BatchEstimator {
 public:
  virtual ~BatchEstimator() = default;
  virtual BatchResult Solve(const datasets::Scenario& scenario) = 0;
};

}  // namespace phdslam::filters
