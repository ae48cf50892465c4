#include "datasets/scenario.h"

#include "src/models/velocity_motion_model.h"

namespace phdslam::datasets {

std::unique_ptr<models::MotionModel> Scenario::MakeMotionModel() const {
  if (motion == MotionKind::kCar) return std::make_unique<models::CarMotionModel>(car);
  return std::make_unique<models::VelocityMotionModel>();
}

filters::EstimatorContext Scenario::PublicContext() const {
  filters::EstimatorContext c;
  c.initial_pose = initial_pose;
  c.motion = MakeMotionModel();
  c.control_noise_cov = control_noise_cov;
  c.sensor = sensor;
  return c;
}

}  // namespace phdslam::datasets
