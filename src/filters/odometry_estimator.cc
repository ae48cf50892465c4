#include "src/filters/odometry_estimator.h"

#include <utility>

#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {

OdometryEstimator::OdometryEstimator(EstimatorContext context)
    : context_(std::move(context)), pose_(context_.initial_pose) {}

StepOutput OdometryEstimator::Step(const datasets::StepData& step) {
  for (std::size_t i = 0; i + 1 < step.times.size(); ++i) {
    const double dt = step.times[i + 1] - step.times[i];
    const auto j = context_.motion->Jacobians(pose_, step.controls[i], dt);
    pose_ = context_.motion->Predict(pose_, step.controls[i], dt);
    cov_ = j.fx * cov_ * j.fx.transpose() + j.fu * context_.control_noise_cov * j.fu.transpose();
    Symmetrize(cov_);
  }
  map_ = MapEstimate{};
  for (const Measurement& z : step.measurements) {
    map_.means.push_back(models::InverseMeasurement(pose_, z));
    map_.covs.push_back(models::BirthCovariance(pose_, z, context_.sensor.noise_cov));
    map_.log_weights.push_back(0.0);
  }
  StepOutput out;
  out.pose = pose_;
  out.pose_cov = cov_;
  out.diag.map_components = static_cast<int>(map_.size());
  return out;
}

}  // namespace phdslam::filters
