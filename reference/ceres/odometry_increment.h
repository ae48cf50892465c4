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
/// The default position floor, 5 mm, is the size of the linearisation error that the rank-2
/// covariance ignores: with the synthetic Qu = diag(0.8^2, (0.5 deg)^2) and dt = 1 s, the
/// second-order term of f in the control noise (chiefly dv * domega * dt^2 / 2, sideways) has an
/// RMS of 3-4 mm along Sigma's null direction. A floor much below that (the filters' Qn =
/// diag(1e-9, 1e-9, 1e-18) corresponds to 0.03 mm) makes the odometry a near-hard kinematic
/// constraint that true trajectories violate by ~100 sigma, and squares the Jacobian's condition
/// number into the 1e9+ range. The heading is linear in omega, so its floor only needs to keep
/// Sigma invertible for a step without propagation.
struct OdometryNoiseFloor {
  double position_std = 5e-3;  ///< m
  double heading_std = 1e-5;   ///< rad
};

struct OdometryIncrement {
  bool propagated = false;       ///< false when the step has a single time stamp (no motion)
  Pose delta = Pose::Zero();     ///< f(0, u): relative pose in the frame of the previous pose
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
