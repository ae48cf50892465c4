// Velocity (unicycle) motion model of the synthetic scenario, docs/algorithms/models.md section
// 2.1-2.2, with the straight-line limit when |omega| < kStraightLineOmega.
#pragma once

#include "src/models/motion_model.h"

namespace phdslam::models {

class VelocityMotionModel final : public MotionModel {
 public:
  /// Below this |omega| (rad/s) the straight-line limit is used.
  static constexpr double kStraightLineOmega = 1e-9;

  [[nodiscard]] Pose Predict(const Pose& x, const Control& u, double dt) const override;
  [[nodiscard]] MotionJacobians Jacobians(const Pose& x, const Control& u,
                                          double dt) const override;
  [[nodiscard]] std::unique_ptr<MotionModel> Clone() const override {
    return std::make_unique<VelocityMotionModel>(*this);
  }
};

}  // namespace phdslam::models
