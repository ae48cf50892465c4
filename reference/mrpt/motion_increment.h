// The odometry of one filter step as a Gaussian: propagated in the world frame (as every filter
// in phdslam does, docs/algorithms/models.md section 2.4) or expressed as a pose increment in the
// robot frame (the form MRPT's odometry actions take).
#pragma once

#include "datasets/scenario.h"
#include "src/core/types.h"
#include "src/models/motion_model.h"

namespace phdslam::reference {

/// A pose with its covariance.
struct PoseGaussian {
  Pose mean = Pose::Zero();
  Mat3 cov = Mat3::Zero();
};

/// Propagates (mean, cov) over the step's sub-intervals: for each, mean <- f(mean, u_i, dt_i) and
/// cov <- Fx cov Fx^T + Fu Q_u Fu^T (zero-order hold of controls[i] over [times[i],
/// times[i+1]]). A step with a single time stamp returns the input unchanged.
/// Throws std::invalid_argument when controls.size() != times.size() - 1 or a dt is negative.
PoseGaussian PropagateOverStep(const models::MotionModel& motion, const Mat2& control_noise_cov,
                               const datasets::StepData& step, const PoseGaussian& start);

/// The step's motion from pose `from`, as the robot-frame increment d = (dx, dy, dtheta) with
/// from (+) d = PropagateOverStep(from).mean, and its covariance: the world-frame covariance of the
/// propagation from a zero covariance, rotated into the frame of `from`. Composing `from` with a
/// draw from N(d, cov) gives exactly the linearised world-frame Gaussian back.
PoseGaussian RobotFrameIncrement(const models::MotionModel& motion, const Mat2& control_noise_cov,
                                 const datasets::StepData& step, const Pose& from);

/// from (+) d: x + R(theta) d_xy, theta + d_theta (the heading is not wrapped).
Pose ComposePose(const Pose& from, const Vec3& increment);

/// blockdiag(R(theta), 1): maps robot-frame pose perturbations to the world frame.
Mat3 RobotToWorldRotation(double theta);

}  // namespace phdslam::reference
