#include "src/filters/ipl.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <vector>

#include "src/core/angles.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {
namespace {

Mat2 NoiseCov() {
  Mat2 r;
  r << 0.64, 0.0, 0.0, 2.7416e-5;
  return r;
}

TEST(PartitionedIpl, OneIterationEqualsTheStackedKalmanPosterior) {
  const Pose mu0(300.0, 400.0, -0.1);
  Mat3 sigma0;
  sigma0 << 0.7, 0.1, 0.001, 0.1, 0.5, 0.002, 0.001, 0.002, 1e-4;
  std::vector<IplPair> pairs = {
      {Landmark(340.0, 410.0), Mat2::Identity() * 0.3, Measurement(41.0, 0.35)},
      {Landmark(320.0, 350.0), Mat2::Identity() * 0.2, Measurement(53.0, -1.3)},
      {Landmark(390.0, 420.0), Mat2::Identity() * 0.1, Measurement(92.0, 0.3)}};
  const IplResult one = PartitionedIpl(mu0, sigma0, pairs, NoiseCov(), {1, 1e-3});

  // Stacked linear-Gaussian update linearised at the prior mean.
  const int n = static_cast<int>(pairs.size());
  Eigen::MatrixXd h(2 * n, 3);
  Eigen::MatrixXd omega = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  Eigen::VectorXd nu(2 * n);
  for (int i = 0; i < n; ++i) {
    const auto j = models::MeasurementJacobians(mu0, pairs[i].landmark_mean);
    h.block<2, 3>(2 * i, 0) = j.hx;
    omega.block<2, 2>(2 * i, 2 * i) = j.hm * pairs[i].landmark_cov * j.hm.transpose() + NoiseCov();
    Vec2 r = pairs[i].z - models::PredictMeasurement(mu0, pairs[i].landmark_mean);
    r(1) = WrapAngle(r(1));
    nu.segment<2>(2 * i) = r;
  }
  const Eigen::MatrixXd s = h * sigma0 * h.transpose() + omega;
  const Eigen::MatrixXd k = sigma0 * h.transpose() * s.inverse();
  const Vec3 mean = mu0 + k * nu;
  const Mat3 cov = sigma0 - k * s * k.transpose();
  EXPECT_LT((one.mean - mean).norm(), 1e-9);
  EXPECT_LT((one.cov - cov).norm(), 1e-12);
  EXPECT_EQ(one.iterations, 1);
}

TEST(PartitionedIpl, IteratesToAFixedPointAndStopsOnKl) {
  const Pose truth(10.0, -5.0, 0.2);
  const Pose mu0(11.5, -6.0, 0.25);
  const Mat3 sigma0 = Vec3(2.0, 2.0, 0.01).asDiagonal();
  std::vector<IplPair> pairs;
  for (const Landmark& m :
       {Landmark(40, 5), Landmark(30, -30), Landmark(60, 20), Landmark(20, 15)}) {
    pairs.push_back({m, Mat2::Identity() * 1e-4, models::PredictMeasurement(truth, m)});
  }
  const IplResult r = PartitionedIpl(mu0, sigma0, pairs, NoiseCov(), {20, 1e-10});
  EXPECT_FALSE(r.cholesky_failed);
  EXPECT_GE(r.iterations, 2);
  EXPECT_LT(r.iterations, 20);
  // A further IPL iteration from the converged result changes it by less than the tolerance.
  const IplResult five = PartitionedIpl(mu0, sigma0, pairs, NoiseCov(), {5, 1e-3});
  EXPECT_LE(five.iterations, 5);
  EXPECT_LT((r.mean - truth).head<2>().norm(), (mu0 - truth).head<2>().norm());
}

TEST(PartitionedIpl, TheCallersPriorLinearisationGivesTheSameResultBitForBit) {
  const Pose mu0(300.0, 400.0, -0.1);
  Mat3 sigma0;
  sigma0 << 0.7, 0.1, 0.001, 0.1, 0.5, 0.002, 0.001, 0.002, 1e-4;
  std::vector<IplPair> pairs = {
      {Landmark(340.0, 410.0), Mat2::Identity() * 0.3, Measurement(41.0, 0.35)},
      {Landmark(320.0, 350.0), Mat2::Identity() * 0.2, Measurement(53.0, -1.3)},
      {Landmark(390.0, 420.0), Mat2::Identity() * 0.1, Measurement(92.0, 0.3)}};
  const IplResult evaluated = PartitionedIpl(mu0, sigma0, pairs, NoiseCov(), {5, 1e-9});
  std::vector<models::PredictionWithJacobians> at_prior;
  for (const IplPair& pair : pairs) {
    at_prior.push_back(models::PredictWithJacobians(mu0, pair.landmark_mean));
  }
  for (std::size_t i = 0; i < pairs.size(); ++i) pairs[i].at_prior = &at_prior[i];
  const IplResult given = PartitionedIpl(mu0, sigma0, pairs, NoiseCov(), {5, 1e-9});
  EXPECT_GE(given.iterations, 2);
  EXPECT_EQ(given.iterations, evaluated.iterations);
  EXPECT_EQ(given.mean, evaluated.mean);
  EXPECT_EQ(given.cov, evaluated.cov);
  // The given values are the ones used: a different prior prediction moves the first iterate.
  at_prior[0].z_hat(0) += 1.0;
  const IplResult moved = PartitionedIpl(mu0, sigma0, pairs, NoiseCov(), {1, 1e-9});
  const IplResult first = PartitionedIpl(mu0, sigma0, pairs, NoiseCov(), {1, 1e-9});
  EXPECT_EQ(moved.mean, first.mean);  // both read the moved z_hat
  pairs[0].at_prior = nullptr;
  EXPECT_NE(PartitionedIpl(mu0, sigma0, pairs, NoiseCov(), {1, 1e-9}).mean, moved.mean);
}

TEST(PartitionedIpl, NoPairsReturnsThePrior) {
  const Pose mu0(1, 2, 3);
  const Mat3 s = Mat3::Identity();
  const IplResult r = PartitionedIpl(mu0, s, {}, NoiseCov(), {});
  EXPECT_EQ(r.mean, mu0);
  EXPECT_EQ(r.cov, s);
}

TEST(PartitionedIpl, KeepsThePriorWhenTheFirstIterateIsNotPositiveDefinite) {
  const Pose mu0(0, 0, 0);
  const Mat3 zero = Mat3::Zero();
  const std::vector<IplPair> pairs = {{Landmark(10, 0), Mat2::Identity(), Measurement(10, 0)}};
  const IplResult r = PartitionedIpl(mu0, zero, pairs, NoiseCov(), {});
  EXPECT_TRUE(r.cholesky_failed);
  EXPECT_EQ(r.mean, mu0);
  EXPECT_EQ(r.cov, zero);
}

TEST(KlDivergence3, IsZeroForEqualAndMatchesClosedForm) {
  const Mat3 p = Vec3(1.0, 2.0, 3.0).asDiagonal();
  EXPECT_NEAR(KlDivergence3(Vec3::Zero(), p, Vec3::Zero(), p), 0.0, 1e-14);
  const Mat3 q = Vec3(2.0, 2.0, 3.0).asDiagonal();
  const Vec3 dm(1.0, 0.0, 0.0);
  // 1/2 [tr(Q^-1 P) - 3 + dm' Q^-1 dm + ln det Q - ln det P] = 1/2 [2.5 - 3 + 0.5 + ln 2]
  EXPECT_NEAR(KlDivergence3(Vec3::Zero(), p, dm, q), 0.5 * std::log(2.0), 1e-14);
}

}  // namespace
}  // namespace phdslam::filters
