#include "datasets/scenario.h"

#include "src/models/velocity_motion_model.h"

namespace phdslam::datasets {

std::unique_ptr<models::MotionModel> Scenario::MakeMotionModel() const {
  if (motion == MotionKind::kCar) return std::make_unique<models::CarMotionModel>(car);
  return std::make_unique<models::VelocityMotionModel>();
}

}  // namespace phdslam::datasets
