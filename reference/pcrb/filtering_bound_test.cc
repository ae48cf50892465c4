#include "reference/pcrb/filtering_bound.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "reference/ceres/test_scenario.h"
#include "reference/pcrb/linearise.h"
#include "reference/pcrb/test_batch_information.h"
#include "reference/pcrb/test_linear_gaussian.h"

namespace phdslam::reference::pcrb {
namespace {

double MaxAbsDifference(const Mat3& a, const Mat3& b) { return (a - b).cwiseAbs().maxCoeff(); }

TEST(FilteringBound, EqualsTheInformationFilterOfALinearGaussianProblemAtFullDetection) {
  RandomStream rng(1);
  const LinearisedSlam model = testing::LinearGaussianModel(40, 4, 1.0, rng);
  const FilteringBound bound = ComputeFilteringBound(model);
  const std::vector<Mat3> kf = testing::InformationFilterPoseCovs(model);
  ASSERT_EQ(bound.pose_covs.size(), kf.size());
  for (std::size_t k = 0; k < kf.size(); ++k) {
    EXPECT_LT(MaxAbsDifference(bound.pose_covs[k], kf[k]), 1e-9) << "step " << k;
  }
  // The position becomes uncertain through the control noise; the heading keeps its prior.
  EXPECT_GT(bound.pose_covs.back()(0, 0), bound.pose_covs.front()(0, 0));
  EXPECT_NEAR(bound.pose_covs.back()(2, 2), 0.03, 1e-12);
}

TEST(FilteringBound, EqualsTheInformationFilterWithAKnownDetectionSequence) {
  RandomStream rng(7);
  const LinearisedSlam model = testing::LinearGaussianModel(60, 5, 0.4, rng);
  const FilteringBound bound = ComputeFilteringBound(model);
  const std::vector<Mat3> kf = testing::InformationFilterPoseCovs(model);
  for (std::size_t k = 0; k < kf.size(); ++k) {
    EXPECT_LT(MaxAbsDifference(bound.pose_covs[k], kf[k]), 1e-9) << "step " << k;
  }
}

LinearisedSlam CircleModel(DetectionModel detection, double pd, int steps) {
  reference::testing::CircleScenarioOptions o;
  o.steps = steps;
  o.landmarks = 8;
  o.detection_probability = pd;
  o.first_step_propagates = true;
  PcrbParams p;
  p.detection_model = detection;
  return Linearise(reference::testing::MakeCircleScenario(o), p, 1, "pcrb");
}

TEST(FilteringBound, RecursionEqualsTheBatchInverseOfTheFullInformation) {
  const LinearisedSlam model = CircleModel(DetectionModel::kConditioned, 0.8, 40);
  const FilteringBound bound = ComputeFilteringBound(model);
  for (std::size_t last : {std::size_t{9}, std::size_t{39}}) {
    const testing::BatchBound batch = testing::DenseBatchBound(model, last);
    const Mat3& p = bound.pose_covs[last];
    EXPECT_LT(MaxAbsDifference(p, batch.pose_covs[last]), 1e-9 * p.norm()) << "step " << last;
  }
  const testing::BatchBound all = testing::DenseBatchBound(model, 39);
  for (int i = 0; i < model.landmarks; ++i) {
    const int c = all.landmark_column[static_cast<std::size_t>(i)];
    ASSERT_EQ(c >= 0, static_cast<bool>(bound.landmark_seen[static_cast<std::size_t>(i)]));
    if (c < 0) continue;
    const Mat2 batch = all.covariance.block<2, 2>(c, c);
    EXPECT_LT((bound.landmark_covs[static_cast<std::size_t>(i)] - batch).cwiseAbs().maxCoeff(),
              1e-9 * batch.norm())
        << "landmark " << i;
  }
}

TEST(FilteringBound, StaysSymmetricPositiveSemiDefinite) {
  const FilteringBound bound = ComputeFilteringBound(CircleModel(DetectionModel::kIrf, 0.95, 100));
  for (const Mat3& p : bound.pose_covs) {
    EXPECT_EQ(p, p.transpose());
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Mat3>(p).eigenvalues().minCoeff(), -1e-12);
  }
}

// The Monte Carlo mean squared position error of the Kalman filter over 3000 runs lies within its
// confidence interval of the bound: E|e|^2 = tr P_xy, var |e|^2 = 2 tr(P_xy^2) for a Gaussian e.
TEST(FilteringBound, KalmanMonteCarloMseMatchesTheBound) {
  RandomStream detections(5);
  const LinearisedSlam model = testing::LinearGaussianModel(25, 3, 0.6, detections);
  const std::vector<Landmark> landmarks = {Landmark(3.0, 1.0), Landmark(-2.0, 4.0),
                                           Landmark(0.5, -3.0)};
  const Mat2 p = ComputeFilteringBound(model).pose_covs.back().topLeftCorner<2, 2>();
  RandomStream rng(11);
  const int runs = 3000;
  double sum = 0.0;
  for (int i = 0; i < runs; ++i) sum += testing::KalmanSquaredPositionError(model, landmarks, rng);
  const double mse = sum / runs;
  const double se = std::sqrt(2.0 * (p * p).trace() / runs);
  EXPECT_NEAR(mse, p.trace(), 3.0 * se) << "bound " << p.trace() << ", SE " << se;
}

TEST(FilteringBound, RefusesAnUnknownLandmark) {
  RandomStream rng(1);
  LinearisedSlam model = testing::LinearGaussianModel(3, 2, 1.0, rng);
  model.steps[1].detections[0].landmark = 5;
  EXPECT_THROW(ComputeFilteringBound(model), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference::pcrb
