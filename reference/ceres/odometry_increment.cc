#include "reference/ceres/odometry_increment.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "src/core/gaussian.h"

namespace phdslam::reference {

OdometryIncrement ComposeStepOdometry(const models::MotionModel& model,
                                      const datasets::StepData& step, const Mat2& qu,
                                      const OdometryNoiseFloor& floor) {
  if (step.times.empty()) throw std::invalid_argument("ComposeStepOdometry: step has no times");
  if (step.controls.size() + 1 != step.times.size()) {
    throw std::invalid_argument("ComposeStepOdometry: expected times.size() - 1 = " +
                                std::to_string(step.times.size() - 1) + " controls, got " +
                                std::to_string(step.controls.size()));
  }
  OdometryIncrement inc;
  Mat3 p = Mat3::Zero();
  for (std::size_t i = 0; i + 1 < step.times.size(); ++i) {
    const double dt = step.times[i + 1] - step.times[i];
    const models::MotionJacobians j = model.Jacobians(inc.delta, step.controls[i], dt);
    inc.delta = model.Predict(inc.delta, step.controls[i], dt);
    p = j.fx * p * j.fx.transpose() + j.fu * qu * j.fu.transpose();
    inc.propagated = true;
  }
  const double sp2 = floor.position_std * floor.position_std;
  p += Vec3(sp2, sp2, floor.heading_std * floor.heading_std).asDiagonal();
  Symmetrize(p);
  inc.covariance = p;
  return inc;
}

Pose ComposeRelative(const Pose& x, const Pose& d) {
  const double c = std::cos(x(2));
  const double s = std::sin(x(2));
  return {x(0) + c * d(0) - s * d(1), x(1) + s * d(0) + c * d(1), x(2) + d(2)};
}

Pose RelativePose(const Pose& x_a, const Pose& x_b) {
  const double c = std::cos(x_a(2));
  const double s = std::sin(x_a(2));
  const double dx = x_b(0) - x_a(0);
  const double dy = x_b(1) - x_a(1);
  return {c * dx + s * dy, -s * dx + c * dy, x_b(2) - x_a(2)};
}

template <int N>
Eigen::Matrix<double, N, N> WhiteningMatrix(const Eigen::Matrix<double, N, N>& cov) {
  const auto l = CholeskyLower<N>(cov);
  if (!l) throw std::invalid_argument("WhiteningMatrix: covariance is not positive definite");
  const Eigen::Matrix<double, N, N> identity = Eigen::Matrix<double, N, N>::Identity();
  return l->template triangularView<Eigen::Lower>().solve(identity);
}

template Mat2 WhiteningMatrix<2>(const Mat2&);
template Mat3 WhiteningMatrix<3>(const Mat3&);

}  // namespace phdslam::reference
