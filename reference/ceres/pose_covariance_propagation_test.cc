#include "reference/ceres/pose_covariance_propagation.h"

#include <gtest/gtest.h>

namespace phdslam::reference {
namespace {

/// Central-difference Jacobian of x (+) d with respect to x (wrt_x) or d.
Mat3 NumericJacobian(const Pose& x, const Pose& d, bool wrt_x) {
  constexpr double kStep = 1e-6;
  Mat3 j;
  for (int c = 0; c < 3; ++c) {
    Pose xp = x;
    Pose xm = x;
    Pose dp = d;
    Pose dm = d;
    (wrt_x ? xp : dp)(c) += kStep;
    (wrt_x ? xm : dm)(c) -= kStep;
    j.col(c) = (ComposeRelative(xp, dp) - ComposeRelative(xm, dm)) / (2.0 * kStep);
  }
  return j;
}

TEST(PropagatePoseCovariance, IsTheFirstOrderCovarianceOfTheComposedPose) {
  const Pose x(3.0, -1.0, 2.2);
  OdometryIncrement inc;
  inc.propagated = true;
  inc.delta = Pose(0.9, 0.05, 0.1);
  inc.covariance << 0.04, 0.001, 0.002, 0.001, 0.01, 0.0005, 0.002, 0.0005, 0.003;
  Mat3 px;
  px << 0.5, 0.1, 0.02, 0.1, 0.3, -0.01, 0.02, -0.01, 0.05;
  const Mat3 jx = NumericJacobian(x, inc.delta, true);
  const Mat3 jd = NumericJacobian(x, inc.delta, false);
  const Mat3 expected = jx * px * jx.transpose() + jd * inc.covariance * jd.transpose();
  const Mat3 p = PropagatePoseCovariance(x, inc, px);
  EXPECT_LT((p - expected).norm(), 1e-8 * expected.norm()) << p << "\n" << expected;
  // The heading variance adds up; the position picks up the heading's lever arm.
  EXPECT_NEAR(p(2, 2), px(2, 2) + inc.covariance(2, 2), 1e-15);
  const double position_before = px.topLeftCorner<2, 2>().trace();
  const double position_after = p.topLeftCorner<2, 2>().trace();
  EXPECT_GT(position_after, position_before);
}

TEST(PropagatePoseCovariance, LeavesThePoseCovarianceOfAStepWithoutMotion) {
  OdometryIncrement still;
  still.covariance = Mat3::Identity();
  Mat3 px = Vec3(0.1, 0.2, 0.3).asDiagonal();
  EXPECT_EQ(PropagatePoseCovariance(Pose(1.0, 2.0, 0.3), still, px), px);
}

}  // namespace
}  // namespace phdslam::reference
