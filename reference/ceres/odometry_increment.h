// The odometry of one filter step as a relative-pose constraint in the frame of the previous pose.
//
// Both motion models of the project (velocity and car) are equivariant under planar rigid
// motions: propagating from a pose x gives x (+) f(0, u), where (+) composes a relative pose
// [dp; dtheta] given in the frame of x,
//   x (+) d = [p + Rot(theta) dp; theta + dtheta],
// and the propagated covariance is T(theta) Sigma(0) T(theta)^T with T = blkdiag(Rot(theta), 1).
// So the whole step (one or several sub-intervals) is summarised once, from the origin, by the
// increment d = f(0, u) and its covariance Sigma (built with the models' own Jacobians, as the
// filters build theirs), and the odometry residual x_k - f(x_{k-1}, u) rotated into the frame of
// x_{k-1} is whitened by a constant Sigma^{-1/2}. The heading difference is never wrapped.
//
// Sigma = sum_i Phi_i Fu_i Qu Fu_i^T Phi_i^T has rank 2 for a single sub-interval of the velocity
// model (the unicycle cannot slide sideways). The missing direction is filled by a stated floor,
// diag(s_p^2, s_p^2, s_theta^2) added in the frame of x_{k-1}: see OdometryNoiseFloor.
#pragma once

#include "datasets/scenario.h"
#include "src/core/types.h"
#include "src/models/motion_model.h"

namespace phdslam::reference {

/// Floor added to the propagated control-noise covariance of every step (frame of x_{k-1}).
///
/// It only has to make Sigma invertible: the unicycle cannot slide sideways, and a tighter floor
/// keeps the estimate closer to that kinematics. On the paper scenario (seed 1, known
/// association; README.md) the position RMSE is 1.48 / 1.33 / 1.16 / 1.01 / 0.93 / 0.92 / 0.92 m
/// for position floors of 50 / 20 / 10 / 5 / 1 / 0.1 / 0.03 mm (0.03 mm is the filters' Qn).
/// The default, 0.1 mm, is at the plateau while keeping the odometry whitening (~1e4 per metre)
/// three orders of magnitude milder than Qn's heading term. Such a tight floor makes the chain
/// nearly rigid, so the smoother warms up with a looser one (SmootherOptions::warm_start_floor).
/// The heading is linear in omega, so its floor only keeps Sigma invertible for a step without
/// propagation.
struct OdometryNoiseFloor {
  double position_std = 1e-4;  ///< m
  double heading_std = 1e-5;   ///< rad
};

struct OdometryIncrement {
  bool propagated = false;         ///< false when the step has a single time stamp (no motion)
  Pose delta = Pose::Zero();       ///< f(0, u): relative pose in the frame of the previous pose
  Mat3 covariance = Mat3::Zero();  ///< propagated control noise plus the floor (frame of x_{k-1})
};

/// Composes the sub-intervals of `step` from the origin with `model` (zero-order hold) and
/// propagates the control-noise covariance qu with the model's Jacobians.
OdometryIncrement ComposeStepOdometry(const models::MotionModel& model,
                                      const datasets::StepData& step, const Mat2& qu,
                                      const OdometryNoiseFloor& floor);

/// x (+) d: applies a relative pose d given in the frame of x. The heading is not wrapped.
Pose ComposeRelative(const Pose& x, const Pose& d);

/// x_b (-) x_a: the pose x_b in the frame of x_a (inverse of ComposeRelative).
Pose RelativePose(const Pose& x_a, const Pose& x_b);

/// W with W^T W = cov^{-1} (W = L^{-1} for cov = L L^T). Throws std::invalid_argument when cov
/// is not positive definite.
template <int N>
Eigen::Matrix<double, N, N> WhiteningMatrix(const Eigen::Matrix<double, N, N>& cov);

}  // namespace phdslam::reference
