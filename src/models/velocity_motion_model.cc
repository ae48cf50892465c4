#include "src/models/velocity_motion_model.h"

#include <cmath>

namespace phdslam::models {

Pose VelocityMotionModel::Predict(const Pose& x, const Control& u, double dt) const {
  const double v = u(0);
  const double w = u(1);
  const double th = x(2);
  Pose out;
  if (std::abs(w) < kStraightLineOmega) {
    out << x(0) + v * dt * std::cos(th), x(1) + v * dt * std::sin(th), th + w * dt;
    return out;
  }
  const double th1 = th + w * dt;
  out << x(0) + v / w * (std::sin(th1) - std::sin(th)),
      x(1) + v / w * (std::cos(th) - std::cos(th1)), th1;
  return out;
}

MotionJacobians VelocityMotionModel::Jacobians(const Pose& x, const Control& u, double dt) const {
  const double v = u(0);
  const double w = u(1);
  const double th = x(2);
  MotionJacobians j;
  j.fx.setIdentity();
  if (std::abs(w) < kStraightLineOmega) {
    const double c = std::cos(th);
    const double s = std::sin(th);
    j.fx(0, 2) = -v * dt * s;
    j.fx(1, 2) = v * dt * c;
    j.fu << dt * c, -0.5 * v * dt * dt * s,  //
        dt * s, 0.5 * v * dt * dt * c,       //
        0.0, dt;
    return j;
  }
  const double th1 = th + w * dt;
  const double s0 = std::sin(th);
  const double c0 = std::cos(th);
  const double s1 = std::sin(th1);
  const double c1 = std::cos(th1);
  j.fx(0, 2) = v / w * (c1 - c0);
  j.fx(1, 2) = v / w * (s1 - s0);
  j.fu(0, 0) = (s1 - s0) / w;
  j.fu(1, 0) = (c0 - c1) / w;
  j.fu(2, 0) = 0.0;
  j.fu(0, 1) = v / (w * w) * (s0 - s1) + v * dt / w * c1;
  j.fu(1, 1) = v / (w * w) * (c1 - c0) + v * dt / w * s1;
  j.fu(2, 1) = dt;
  return j;
}

}  // namespace phdslam::models
