// The linearised propagation of a pose Gaussian through a motion model over the sub-intervals of
// one filter step (docs/algorithms/models.md section 2.4, step 2): the one implementation behind
// the RB-PHD-SLAM family's prediction, single-cluster PHD SLAM, dead reckoning, the oracle and
// the MRPT baselines' odometry.
#pragma once

#include "src/core/step_data.h"
#include "src/core/types.h"
#include "src/models/motion_model.h"

namespace phdslam::models {

/// For each sub-interval [times[i], times[i+1]] of `step` (control controls[i] held over it), with
/// the Jacobians Fx, Fu at the mean before the sub-interval: mean <- f(mean, u_i, dt_i) and
/// cov <- Fx cov Fx^T + Fu Q_u Fu^T, symmetrised (so a symmetric positive-definite cov stays
/// so). A step with fewer than two time stamps changes nothing. Checks nothing: callers that read
/// untrusted steps check controls.size() == times.size() - 1 first.
void PropagatePoseGaussian(const MotionModel& motion, const Mat2& control_noise_cov,
                           const StepData& step, Pose& mean, Mat3& cov);

}  // namespace phdslam::models
