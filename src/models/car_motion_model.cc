#include "src/models/car_motion_model.h"

#include <cmath>

namespace phdslam::models {

Pose CarMotionModel::Predict(const Pose& x, const Control& u, double dt) const {
  const double ta = std::tan(u(1));
  const double vc = u(0) / (1.0 - g_.encoder_offset_h / g_.wheelbase_l * ta);
  const double s = std::sin(x(2));
  const double c = std::cos(x(2));
  const double k = ta / g_.wheelbase_l;
  Pose out;
  out << x(0) + dt * vc * (c - k * (g_.laser_a * s + g_.laser_b * c)),
      x(1) + dt * vc * (s + k * (g_.laser_a * c - g_.laser_b * s)), x(2) + dt * vc * k;
  return out;
}

MotionJacobians CarMotionModel::Jacobians(const Pose& x, const Control& u, double dt) const {
  const double alpha = u(1);
  const double ta = std::tan(alpha);
  const double vc = u(0) / (1.0 - g_.encoder_offset_h / g_.wheelbase_l * ta);
  const double s = std::sin(x(2));
  const double c = std::cos(x(2));
  const double k = ta / g_.wheelbase_l;
  const double a = g_.laser_a;
  const double b = g_.laser_b;
  MotionJacobians j;
  j.fx.setIdentity();
  j.fx(0, 2) = -dt * vc * (s + k * (a * c - b * s));
  j.fx(1, 2) = dt * vc * (c - k * (a * s + b * c));
  j.fu(0, 0) = dt * (c - k * (a * s + b * c));
  j.fu(1, 0) = dt * (s + k * (a * c - b * s));
  j.fu(2, 0) = dt * k;
  const double ca = std::cos(alpha);
  const double g = dt * vc / (g_.wheelbase_l * ca * ca);
  j.fu(0, 1) = -g * (a * s + b * c);
  j.fu(1, 1) = g * (a * c - b * s);
  j.fu(2, 1) = g;
  return j;
}

}  // namespace phdslam::models
