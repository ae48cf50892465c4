#include "reference/ceres/start_trajectory.h"

#include <chrono>
#include <stdexcept>
#include <string>
#include <utility>

namespace phdslam::reference {

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
