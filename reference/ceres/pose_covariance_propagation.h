// The covariance of a pose propagated by one step's odometry increment (odometry_increment.h):
// x' = x (+) d with x ~ (x, Px) and d ~ (d, Sigma) independent, to first order
//   Px' = Jx Px Jx^T + Jd Sigma Jd^T,
// Jx = d(x (+) d)/dx = [I, dRot(theta) dp; 0, 1], Jd = d(x (+) d)/dd = blkdiag(Rot(theta), 1).
// Shared by the sequential association pass and the incremental solve's own association, which
// gate each scan on the propagated pose covariance.
#pragma once

#include <cmath>

#include "reference/ceres/odometry_increment.h"
#include "src/core/types.h"

namespace phdslam::reference {

/// Jx = d(x (+) inc.delta)/dx at x (the identity when the step does not propagate).
inline Mat3 PoseCompositionJacobian(const Pose& x, const OdometryIncrement& inc) {
  Mat3 jx = Mat3::Identity();
  if (!inc.propagated) return jx;
  const double c = std::cos(x(2));
  const double s = std::sin(x(2));
  jx(0, 2) = -s * inc.delta(0) - c * inc.delta(1);
  jx(1, 2) = c * inc.delta(0) - s * inc.delta(1);
  return jx;
}

/// Covariance of x (+) inc.delta given that of x (px) and inc.covariance (in the frame of x);
/// px itself when the step does not propagate. Not symmetrized: a caller that stores the result
/// symmetrizes it where it keeps its covariances.
/// Inline: it runs once per step of every association pass.
inline Mat3 PropagatePoseCovariance(const Pose& x, const OdometryIncrement& inc, const Mat3& px) {
  if (!inc.propagated) return px;
  const double c = std::cos(x(2));
  const double s = std::sin(x(2));
  const Mat3 jx = PoseCompositionJacobian(x, inc);
  Mat3 jd = Mat3::Identity();
  jd.topLeftCorner<2, 2>() << c, -s, s, c;
  return jx * px * jx.transpose() + jd * inc.covariance * jd.transpose();
}

}  // namespace phdslam::reference
