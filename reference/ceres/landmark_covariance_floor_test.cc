#include "reference/ceres/landmark_covariance_floor.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <limits>

#include "reference/ceres/linear_prior.h"

namespace phdslam::reference {
namespace {

double SmallestEigenvalue(const Mat2& m) {
  return Eigen::SelfAdjointEigenSolver<Mat2>(m).eigenvalues()(0);
}

TEST(FlooredLandmarkCovariance, KeepsAPositiveDefiniteCovariance) {
  Mat2 cov;
  cov << 0.04, 0.01, 0.01, 0.09;
  const Mat2 out = FlooredLandmarkCovariance(cov);
  EXPECT_LT((out - cov).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(out(0, 1), out(1, 0));
}

TEST(FlooredLandmarkCovariance, FloorsAnIndefiniteMarginalSoThatItBecomesAPrior) {
  // Rounding in a near-singular window: rank one plus a small negative eigenvalue.
  Mat2 cov;
  cov << 1.0, 1.0 + 1e-9, 1.0 + 1e-9, 1.0;
  ASSERT_LT(SmallestEigenvalue(cov), 0.0);
  Vec2 landmark = Vec2::Zero();
  EXPECT_THROW(static_cast<void>(GaussianPrior(landmark.data(), landmark, cov)),
               std::invalid_argument);
  const Mat2 out = FlooredLandmarkCovariance(cov);
  EXPECT_NEAR(SmallestEigenvalue(out), kLandmarkVarianceFloor, 1e-12);
  EXPECT_NEAR(out(0, 0), cov(0, 0), 1e-7);
  EXPECT_EQ(out(0, 1), out(1, 0));
  EXPECT_NO_THROW(static_cast<void>(GaussianPrior(landmark.data(), landmark, out)));
}

TEST(FlooredLandmarkCovariance, SymmetrisesAnAsymmetricInput) {
  Mat2 cov;
  cov << 0.04, 0.012, 0.008, 0.09;
  const Mat2 out = FlooredLandmarkCovariance(cov);
  EXPECT_EQ(out(0, 1), out(1, 0));
  EXPECT_NEAR(out(0, 1), 0.01, 1e-15);
}

TEST(FlooredLandmarkCovariance, ReplacesANonFiniteCovarianceByTheIdentity) {
  Mat2 cov = Mat2::Identity() * 0.04;
  cov(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(FlooredLandmarkCovariance(cov), Mat2::Identity());
}

}  // namespace
}  // namespace phdslam::reference
