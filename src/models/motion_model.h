// Motion model interface: propagates a pose over one sub-interval of a filter step and gives the
// Jacobians with respect to the pose (Fx) and the control (Fu) at the propagation point.
#pragma once

#include <memory>

#include "src/core/types.h"

namespace phdslam::models {

struct MotionJacobians {
  Mat3 fx;
  Mat32 fu;
};

class MotionModel {
 public:
  virtual ~MotionModel() = default;
  /// x' = f(x, u, dt).
  [[nodiscard]] virtual Pose Predict(const Pose& x, const Control& u, double dt) const = 0;
  /// Jacobians of f at (x, u, dt) as the reference implementation computes them.
  [[nodiscard]] virtual MotionJacobians Jacobians(const Pose& x, const Control& u,
                                                  double dt) const = 0;
  [[nodiscard]] virtual std::unique_ptr<MotionModel> Clone() const = 0;
};

}  // namespace phdslam::models
