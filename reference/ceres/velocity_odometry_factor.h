// Odometry factor of a step with one sub-interval of the velocity (unicycle) model, whitened in
// control space: the exact inverse of the motion model.
//
// A unicycle step from x_a with control (v, omega) over dt ends at x_b whose position, in the
// frame of x_a, lies on the chord at angle h = omega dt / 2 and at signed length
// 2 (v / omega) sin(h); the heading turns by 2 h. So the relative pose
// [bx, by, dtheta] = x_b (-) x_a determines the control that explains it and a kinematic
// constraint:
//
//   omega_hat = dtheta / dt,   v_hat = along * (h / sin h) / dt,   h = dtheta / 2,
//   along   =  bx cos h + by sin h      (signed chord length),
//   lateral = -bx sin h + by cos h      (0 for every reachable pose),
//
//   r = [W_u ([v_hat; omega_hat] - u_odometry);  lateral / lateral_std],   W_u^T W_u = Qu^-1.
//
// The first two residuals are the control noise itself, so this factor is the exact likelihood
// of the odometry (no linearisation in the control noise); the third is the unicycle's
// no-sideways-slip constraint, which true trajectories satisfy exactly, softened by
// lateral_std only to keep the problem well conditioned. Compare the pose-space OdometryFactor,
// whose rank-2 propagated covariance is a first-order approximation that true increments
// violate by the second-order term (mm per step, README.md). The heading difference is not
// wrapped. Automatic differentiation, as for OdometryFactor.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <cmath>

#include "src/core/types.h"

namespace phdslam::reference {

class VelocityOdometryFactor {
 public:
  VelocityOdometryFactor(const Control& odometry, double dt, const Mat2& control_whitening,
                         double lateral_std)
      : odometry_(odometry), dt_(dt), whitening_(control_whitening), lateral_std_(lateral_std) {}

  /// h / sin(h), with its Taylor series near 0 (relative error < 1e-17 for |h| < 1e-4).
  template <typename T>
  static T HalfAngleRatio(const T& h) {
    using std::abs;
    using std::sin;
    if (abs(h) < 1e-4) return static_cast<T>(1.0) + h * h / 6.0;
    return h / sin(h);
  }

  template <typename T>
  bool operator()(const T* const pose_a, const T* const pose_b, T* residuals) const {
    using std::cos;
    using std::sin;
    const T c = cos(pose_a[2]);
    const T s = sin(pose_a[2]);
    const T dx = pose_b[0] - pose_a[0];
    const T dy = pose_b[1] - pose_a[1];
    const T bx = c * dx + s * dy;
    const T by = -s * dx + c * dy;
    const T dtheta = pose_b[2] - pose_a[2];
    const T h = dtheta / 2.0;
    const T ch = cos(h);
    const T sh = sin(h);
    const T along = bx * ch + by * sh;
    const T lateral = -bx * sh + by * ch;
    Eigen::Matrix<T, 2, 1> e;
    e(0) = along * HalfAngleRatio(h) / dt_ - odometry_(0);
    e(1) = dtheta / dt_ - odometry_(1);
    const Eigen::Matrix<T, 2, 1> w = whitening_.template cast<T>() * e;
    residuals[0] = w(0);
    residuals[1] = w(1);
    residuals[2] = lateral / lateral_std_;
    return true;
  }

  static ceres::CostFunction* Create(const Control& odometry, double dt,
                                     const Mat2& control_whitening, double lateral_std) {
    return new ceres::AutoDiffCostFunction<VelocityOdometryFactor, 3, 3, 3>(
        new VelocityOdometryFactor(odometry, dt, control_whitening, lateral_std));
  }

 private:
  Control odometry_;
  double dt_;
  Mat2 whitening_;
  double lateral_std_;
};

}  // namespace phdslam::reference
