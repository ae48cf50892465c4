// Odometry factor between consecutive poses x_{k-1} (a) and x_k (b):
//
//   e = [Rot(theta_a)^T (p_b - p_a) - dp;  theta_b - theta_a - dtheta],   r = W e,
//
// where d = [dp; dtheta] = f(0, u) is the step's odometry increment and W^T W = Sigma^{-1} its
// whitening (odometry_increment.h). This is x_k - f(x_{k-1}, u) expressed in the frame of
// x_{k-1}, where the propagated covariance does not depend on the heading. The heading
// difference is not wrapped: headings are never wrapped in this project.
//
// Automatic differentiation: the functor is a few lines of trigonometry in theta_a, so the
// Jacobian comes from Ceres' dual numbers with no hand-derived formula to keep in step. (The
// motion model itself is not differentiated here: it enters only through the constant d and
// Sigma, computed once per step with the model's own Predict and Jacobians.)
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <cmath>

#include "src/core/types.h"

namespace phdslam::reference {

class OdometryFactor {
 public:
  OdometryFactor(const Pose& delta, const Mat3& whitening) : delta_(delta), whitening_(whitening) {}

  template <typename T>
  bool operator()(const T* const pose_a, const T* const pose_b, T* residuals_ptr) const {
    using std::cos;
    using std::sin;
    const T c = cos(pose_a[2]);
    const T s = sin(pose_a[2]);
    const T dx = pose_b[0] - pose_a[0];
    const T dy = pose_b[1] - pose_a[1];
    Eigen::Matrix<T, 3, 1> e;
    e(0) = c * dx + s * dy - static_cast<T>(delta_(0));
    e(1) = -s * dx + c * dy - static_cast<T>(delta_(1));
    e(2) = pose_b[2] - pose_a[2] - static_cast<T>(delta_(2));
    Eigen::Map<Eigen::Matrix<T, 3, 1>> residuals(residuals_ptr);
    residuals = whitening_.template cast<T>() * e;
    return true;
  }

  static ceres::CostFunction* Create(const Pose& delta, const Mat3& whitening) {
    return new ceres::AutoDiffCostFunction<OdometryFactor, 3, 3, 3>(
        new OdometryFactor(delta, whitening));
  }

 private:
  Pose delta_;
  Mat3 whitening_;
};

}  // namespace phdslam::reference
