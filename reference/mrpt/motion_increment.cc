#include "reference/mrpt/motion_increment.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "src/core/gaussian.h"
#include "src/models/pose_propagation.h"

namespace phdslam::reference {

PoseGaussian PropagateOverStep(const models::MotionModel& motion, const Mat2& control_noise_cov,
                               const datasets::StepData& step, const PoseGaussian& start) {
  if (!step.times.empty() && step.controls.size() + 1 != step.times.size()) {
    throw std::invalid_argument("StepData: expected controls.size() == times.size() - 1, got " +
                                std::to_string(step.controls.size()) + " controls for " +
                                std::to_string(step.times.size()) + " time stamps");
  }
  for (std::size_t i = 0; i + 1 < step.times.size(); ++i) {
    const double dt = step.times[i + 1] - step.times[i];
    if (!(dt >= 0.0)) {
      throw std::invalid_argument("StepData: time stamps must not decrease (sub-interval " +
                                  std::to_string(i) + " has dt = " + std::to_string(dt) + ")");
    }
  }
  PoseGaussian out = start;
  models::PropagatePoseGaussian(motion, control_noise_cov, step, out.mean, out.cov);
  return out;
}

Mat3 RobotToWorldRotation(double theta) {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  Mat3 r;
  r << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  return r;
}

Pose ComposePose(const Pose& from, const Vec3& increment) {
  return from + RobotToWorldRotation(from(2)) * increment;
}

PoseGaussian RobotFrameIncrement(const models::MotionModel& motion, const Mat2& control_noise_cov,
                                 const datasets::StepData& step, const Pose& from) {
  const PoseGaussian end =
      PropagateOverStep(motion, control_noise_cov, step, PoseGaussian{from, Mat3::Zero()});
  const Mat3 to_robot = RobotToWorldRotation(from(2)).transpose();
  PoseGaussian d;
  d.mean = to_robot * (end.mean - from);
  d.cov = to_robot * end.cov * to_robot.transpose();
  Symmetrize(d.cov);
  return d;
}

}  // namespace phdslam::reference
