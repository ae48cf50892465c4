// The consistency statistics against distributions known in closed form: NEES of Gaussian draws
// and NIS of a linear Kalman filter on data simulated from its own model.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <vector>

#include "src/core/random.h"
#include "src/filters/innovation_stats.h"
#include "validation/metrics/chi_square.h"
#include "validation/metrics/nees.h"

namespace phdslam::validation {
namespace {

// Kolmogorov-Smirnov distance between the sample and the chi-square(dof) distribution function.
double KsDistance(std::vector<double> sample, double dof) {
  std::sort(sample.begin(), sample.end());
  const double n = static_cast<double>(sample.size());
  double d = 0.0;
  for (std::size_t i = 0; i < sample.size(); ++i) {
    const double f = ChiSquareCdf(sample[i], dof);
    d = std::max({d, f - static_cast<double>(i) / n, static_cast<double>(i + 1) / n - f});
  }
  return d;
}

TEST(Consistency, NeesOfGaussianDrawsFollowsChiSquare3) {
  RandomStream rng(20261123);
  Mat3 cov;
  cov << 0.5, 0.1, 0.02, 0.1, 0.3, -0.01, 0.02, -0.01, 0.05;
  const Mat3 l = Eigen::LLT<Mat3>(cov).matrixL();
  const Pose mean(10.0, -4.0, 1.2);
  std::vector<double> nees;
  constexpr int kDraws = 4000;
  for (int i = 0; i < kDraws; ++i) {
    const Vec3 xi(rng.Normal(), rng.Normal(), rng.Normal());
    nees.push_back(PoseNees(mean + l * xi, mean, cov));
  }
  // 5 % critical value of the KS statistic: 1.358 / sqrt(n).
  const double critical = 1.358 / std::sqrt(static_cast<double>(kDraws));
  EXPECT_LT(KsDistance(nees, 3.0), critical);
  // A covariance twice too small (an overconfident filter) is rejected by the same test.
  std::vector<double> overconfident;
  for (double v : nees) overconfident.push_back(2.0 * v);
  EXPECT_GT(KsDistance(overconfident, 3.0), critical);
  // Coverage of the 95 % ellipsoid.
  const double threshold = EllipsoidThreshold(3);
  const double inside = static_cast<double>(std::count_if(
                            nees.begin(), nees.end(), [&](double v) { return v <= threshold; })) /
                        kDraws;
  EXPECT_NEAR(inside, 0.95, 3.0 * std::sqrt(0.95 * 0.05 / kDraws));
}

// NIS of a 2-D random-walk Kalman filter observing its state directly, with the bounds of the
// run-averaged NIS (chi-square with 2 x steps degrees of freedom over the steps).
double KalmanNisMean(double assumed_noise_scale, int steps) {
  RandomStream rng(7);
  const Mat2 q = Vec2(0.04, 0.09).asDiagonal();
  Mat2 r;
  r << 0.25, 0.05, 0.05, 0.16;
  const Mat2 lq = Eigen::LLT<Mat2>(q).matrixL();
  const Mat2 lr = Eigen::LLT<Mat2>(r).matrixL();
  Vec2 truth = Vec2::Zero();
  Vec2 x = Vec2::Zero();
  Mat2 p = Mat2::Identity() * 1e-6;
  filters::InnovationStats nis;
  for (int k = 0; k < steps; ++k) {
    truth += lq * Vec2(rng.Normal(), rng.Normal());
    const Vec2 z = truth + lr * Vec2(rng.Normal(), rng.Normal());
    p += q;
    const Vec2 nu = z - x;
    const Mat2 s = p + assumed_noise_scale * r;
    nis.Add(nu, s);
    const Mat2 gain = p * s.inverse();
    x += gain * nu;
    p = (Mat2::Identity() - gain) * p;
    p = 0.5 * (p + p.transpose()).eval();
  }
  EXPECT_EQ(nis.count, steps);
  return nis.nis_sum / nis.count;
}

TEST(Consistency, NisOfALinearKalmanFilterLiesInsideItsBounds) {
  constexpr int kSteps = 2000;
  const double lower = ChiSquareQuantile(0.025, 2.0 * kSteps) / kSteps;
  const double upper = ChiSquareQuantile(0.975, 2.0 * kSteps) / kSteps;
  const double consistent = KalmanNisMean(1.0, kSteps);
  EXPECT_GE(consistent, lower);
  EXPECT_LE(consistent, upper);
  // A filter that assumes a quarter of the measurement noise is caught by the upper bound.
  EXPECT_GT(KalmanNisMean(0.25, kSteps), upper);
}

TEST(Consistency, InnovationStatsSkipsANonPositiveDefiniteCovariance) {
  filters::InnovationStats nis;
  nis.Add(Vec2(1.0, 0.0), Mat2::Zero());
  EXPECT_EQ(nis.count, 0);
  nis.Add(Vec2(1.0, 2.0), Vec2(1.0, 4.0).asDiagonal());
  EXPECT_EQ(nis.count, 1);
  EXPECT_DOUBLE_EQ(nis.nis_sum, 2.0);
}

}  // namespace
}  // namespace phdslam::validation
