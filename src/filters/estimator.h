// The estimator interface shared by the system under test, the oracle and the baselines.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "src/core/step_data.h"
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
};

/// Diagnostics of one step, kept in the run record.
struct StepDiagnostics {
  double ess = 1.0;  ///< effective sample size after the update (before resampling)
  bool resampled = false;
  int hypotheses = 0;      ///< components of the importance density (mean over particles)
  int map_components = 0;  ///< GM-PHD components (active + passive) of the best particle
  /// NIS of the estimate's associated measurements (innovation_stats.h): the sum of
  /// nu' S^-1 nu over them and their count, with the S the filter used; 0 / 0 when the
  /// estimator reports none.
  double nis_sum = 0.0;
  int nis_count = 0;
};

struct StepOutput {
  Pose pose = Pose::Zero();
  std::optional<Mat3> pose_cov;  ///< set by estimators that carry a pose covariance
  /// Rao-Blackwellised pose posterior of the step, where the estimator provides one: the moments
  /// of the mixture over particles of each particle's own pose Gaussian before sampling, weighted
  /// by the weights carried into the step (each estimator's documentation says which Gaussian).
  std::optional<Pose> pose_mean_rb;
  std::optional<Mat3> pose_cov_rb;
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
  virtual StepOutput Step(const StepData& step) = 0;
  /// The current map estimate.
  [[nodiscard]] virtual MapEstimate Map() const = 0;
  /// Pose and log-weight of every particle after the last step, for particle filters that
  /// expose them (particle traces); empty otherwise.
  [[nodiscard]] virtual std::vector<std::pair<Pose, double>> ParticleStates() const { return {}; }
};

}  // namespace phdslam::filters
