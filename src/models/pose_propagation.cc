#include "src/models/pose_propagation.h"

#include <cstddef>

#include "src/core/gaussian.h"

namespace phdslam::models {

void PropagatePoseGaussian(const MotionModel& motion, const Mat2& control_noise_cov,
                           const StepData& step, Pose& mean, Mat3& cov) {
  for (std::size_t i = 0; i + 1 < step.times.size(); ++i) {
    const double dt = step.times[i + 1] - step.times[i];
    const MotionJacobians j = motion.Jacobians(mean, step.controls[i], dt);
    mean = motion.Predict(mean, step.controls[i], dt);
    cov = j.fx * cov * j.fx.transpose() + j.fu * control_noise_cov * j.fu.transpose();
    Symmetrize(cov);
  }
}

}  // namespace phdslam::models
