#include "src/filters/odometry_estimator.h"

#include <utility>

#include "src/filters/pose_prediction.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {

OdometryEstimator::OdometryEstimator(EstimatorContext context)
    : context_(std::move(context)), pose_(context_.initial_pose) {}

StepOutput OdometryEstimator::Step(const StepData& step) {
  PredictPoseGaussian(context_, step, Mat3::Zero(), pose_, cov_);
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
