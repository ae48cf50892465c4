#include "reference/ceres/start_trajectory.h"

#include <chrono>
#include <stdexcept>
#include <string>
#include <utility>

#include "src/core/angles.h"

namespace phdslam::reference {

std::vector<OdometryIncrement> StartTrajectoryIncrements(
    const datasets::Scenario& scenario, const std::vector<Pose>& start,
    const std::vector<OdometryIncrement>& odometry) {
  const std::size_t n = scenario.steps.size();
  if (start.size() != n || odometry.size() != n) {
    throw std::invalid_argument("StartTrajectoryIncrements: expected " + std::to_string(n) +
                                " start poses and increments, got " + std::to_string(start.size()) +
                                " and " + std::to_string(odometry.size()));
  }
  std::vector<OdometryIncrement> out = odometry;
  Pose previous = scenario.initial_pose;
  for (std::size_t k = 0; k < n; ++k) {
    if (!start[k].allFinite()) {
      throw std::invalid_argument("StartTrajectoryIncrements: start pose " + std::to_string(k) +
                                  " is not finite");
    }
    if (out[k].propagated) {
      Pose delta = RelativePose(previous, start[k]);
      delta(2) = WrapAngle(delta(2));
      out[k].delta = delta;
    }
    previous = start[k];
  }
  return out;
}

SmoothFromEstimatorStart::SmoothFromEstimatorStart(
    std::unique_ptr<filters::OnlineEstimator> estimator, SmootherOptions options)
    : SmoothFromEstimatorStart(Started{std::move(estimator), nullptr}, std::move(options)) {}

SmoothFromEstimatorStart::SmoothFromEstimatorStart(Started started, SmootherOptions options)
    : lineage_(std::move(started.lineage)),
      estimator_(std::move(started.estimator)),
      options_(std::move(options)) {
  if (!estimator_) throw std::invalid_argument("SmoothFromEstimatorStart: no estimator given");
  if (options_.start_path == StartPath::kBestParticlePath && !lineage_) {
    throw std::invalid_argument(
        "SmoothFromEstimatorStart: start_path best-particle-path needs a particle filter");
  }
  if (options_.association == AssociationMode::kFilter) {
    throw std::invalid_argument(
        "SmoothFromEstimatorStart: the filter association starts from its own filter's "
        "trajectory");
  }
  if (!options_.initial_poses.empty()) {
    throw std::invalid_argument("SmoothFromEstimatorStart: initial_poses is already set");
  }
  options_.Validate();
}

datasets::BatchResult SmoothFromEstimatorStart::Solve(const datasets::Scenario& scenario) {
  if (smoother_) {
    throw std::logic_error("SmoothFromEstimatorStart::Solve: the estimator has already run");
  }
  const auto begin = std::chrono::steady_clock::now();
  start_.clear();
  start_.reserve(scenario.steps.size());
  for (const auto& step : scenario.steps) start_.push_back(estimator_->Step(step.data).pose);
  if (lineage_) {
    start_ = lineage_->lineage().BestFinalPath();
    if (start_.size() != scenario.steps.size()) {
      throw std::logic_error("SmoothFromEstimatorStart: the particle lineage holds " +
                             std::to_string(start_.size()) + " steps, the scenario " +
                             std::to_string(scenario.steps.size()));
    }
  }
  estimator_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  SmootherOptions o = options_;
  o.initial_poses = start_;
  smoother_ = std::make_unique<BatchSmoother>(std::move(o));
  datasets::BatchResult result = smoother_->Solve(scenario);
  result.solve_seconds += estimator_seconds_;
  return result;
}

}  // namespace phdslam::reference
