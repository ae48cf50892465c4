// Dead reckoning: propagates the initial pose with the odometry and its covariance with the
// control noise. Its map is the inverse-model image of every measurement of the last step, so the
// whole evaluation path (trajectory and map metrics) works before any filter exists.
#pragma once

#include "src/filters/estimator.h"

namespace phdslam::filters {

class OdometryEstimator final : public OnlineEstimator {
 public:
  explicit OdometryEstimator(EstimatorContext context);
  StepOutput Step(const StepData& step) override;
  [[nodiscard]] MapEstimate Map() const override { return map_; }

 private:
  EstimatorContext context_;
  Pose pose_;
  Mat3 cov_ = Mat3::Zero();
  MapEstimate map_;
};

}  // namespace phdslam::filters
