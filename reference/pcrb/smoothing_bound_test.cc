#include "reference/pcrb/smoothing_bound.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "reference/ceres/test_scenario.h"
#include "reference/pcrb/linearise.h"
#include "reference/pcrb/test_batch_information.h"
#include "reference/pcrb/test_linear_gaussian.h"

namespace phdslam::reference::pcrb {
namespace {

LinearisedSlam CircleModel(double pd, int steps) {
  reference::testing::CircleScenarioOptions o;
  o.steps = steps;
  o.landmarks = 8;
  o.detection_probability = pd;
  o.first_step_propagates = true;
  return Linearise(reference::testing::MakeCircleScenario(o), PcrbParams{}, 1, "pcrb-smoother");
}

TEST(SmoothingBound, EqualsTheMarginalsOfTheWholeGraphsInverseInformation) {
  const LinearisedSlam model = CircleModel(0.8, 40);
  const std::vector<Mat3> smooth = ComputeSmoothingBound(model, ComputeFilteringBound(model));
  const testing::BatchBound batch = testing::DenseBatchBound(model, 39);
  ASSERT_EQ(smooth.size(), batch.pose_covs.size());
  for (std::size_t k = 0; k < smooth.size(); ++k) {
    const Mat3& b = batch.pose_covs[k];
    EXPECT_LT((smooth[k] - b).cwiseAbs().maxCoeff(), 1e-9 * std::max(b.norm(), 1e-12))
        << "step " << k;
  }
}

TEST(SmoothingBound, IsBelowTheFilteringBoundAndEqualsItAtTheLastStep) {
  const LinearisedSlam model = CircleModel(0.95, 60);
  const FilteringBound filtering = ComputeFilteringBound(model);
  const std::vector<Mat3> smooth = ComputeSmoothingBound(model, filtering);
  for (std::size_t k = 0; k < smooth.size(); ++k) {
    const Mat3 gap = filtering.pose_covs[k] - smooth[k];
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Mat3>(gap).eigenvalues().minCoeff(),
              -1e-9 * filtering.pose_covs[k].norm())
        << "step " << k;
  }
  EXPECT_LT((smooth.back() - filtering.pose_covs.back()).cwiseAbs().maxCoeff(),
            1e-9 * filtering.pose_covs.back().norm());
  EXPECT_LT(smooth[30].trace(), 0.99 * filtering.pose_covs[30].trace());
}

TEST(SmoothingBound, EqualsTheLinearGaussianBatchWithAKnownDetectionSequence) {
  RandomStream rng(3);
  LinearisedSlam model = testing::LinearGaussianModel(30, 3, 0.5, rng);
  model.initial_pose_cov.setZero();  // the batch's poses are functions of the noise alone
  const std::vector<Mat3> smooth = ComputeSmoothingBound(model, ComputeFilteringBound(model));
  const testing::BatchBound batch = testing::DenseBatchBound(model, 29);
  for (std::size_t k = 0; k < smooth.size(); ++k) {
    const Mat3 b = batch.pose_covs[k];
    EXPECT_LT((smooth[k] - b).cwiseAbs().maxCoeff(), 1e-9 * std::max(b.norm(), 1.0))
        << "step " << k;
  }
}

TEST(SmoothingBound, RefusesASingularControlNoise) {
  LinearisedSlam model = CircleModel(0.95, 5);
  model.control_noise_cov(1, 1) = 0.0;
  EXPECT_THROW(ComputeSmoothingBound(model, ComputeFilteringBound(model)), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference::pcrb
