#include "reference/ceres/held_measurement_prior.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "reference/ceres/batch_smoother.h"
#include "reference/ceres/factor_graph.h"
#include "reference/ceres/test_scenario.h"
#include "src/core/angles.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

using testing::CircleScenarioOptions;
using testing::MakeCircleScenario;

Association KnownLabels(const datasets::Scenario& s) {
  Association a;
  for (const auto& step : s.steps) {
    std::vector<int> labels;
    for (int o : step.origin) labels.push_back(o >= 0 ? o : kUnassociated);
    a.push_back(std::move(labels));
  }
  return a;
}

CircleScenarioOptions NoiseFree() {
  CircleScenarioOptions o;
  o.noise = false;
  o.detection_probability = 1.0;
  return o;
}

// Noise-free measurements folded at the true landmarks: the prior's mean is the landmark and its
// information the pose-known information sum Hm^T R^-1 Hm of the folded measurements.
TEST(HeldMeasurementPriors, NoiseFreeFoldAtTheTruthIsTheLandmarkWithItsInformation) {
  const datasets::Scenario s = MakeCircleScenario(NoiseFree());
  const Association a = KnownLabels(s);
  HeldMeasurementPriors priors(s, nullptr);
  priors.FoldUntil(30, a, s.truth.poses, s.truth.landmarks);
  EXPECT_EQ(priors.folded(), 30u);
  const Mat2 r_inv = s.sensor.noise_cov.inverse();
  int with_prior = 0;
  for (std::size_t i = 0; i < s.truth.landmarks.size(); ++i) {
    Mat2 expected = Mat2::Zero();
    for (std::size_t k = 0; k < 30; ++k) {
      for (int l : a[k]) {
        if (l != static_cast<int>(i)) continue;
        const Mat2 hm = models::MeasurementJacobians(s.truth.poses[k], s.truth.landmarks[i]).hm;
        expected += hm.transpose() * r_inv * hm;
      }
    }
    ASSERT_EQ(priors.Has(i), expected.norm() > 0.0) << "landmark " << i;
    if (!priors.Has(i)) continue;
    ++with_prior;
    EXPECT_LT((priors.information(i) - expected).norm(), 1e-9 * expected.norm());
    EXPECT_LT((priors.Mean(i) - s.truth.landmarks[i]).norm(), 1e-9) << "landmark " << i;
  }
  EXPECT_GT(with_prior, 5);
}

// With the robust loss a misread detection folds in with a weight near 0: the prior's mean stays
// at the landmark; with the squared loss it is pulled off.
TEST(HeldMeasurementPriors, TheRobustLossWeighsAMisreadDetectionOut) {
  datasets::Scenario s = MakeCircleScenario(NoiseFree());
  const Association a = KnownLabels(s);
  Measurement& z = s.steps[3].data.measurements[0];
  z(1) = WrapAngle(z(1) + std::numbers::pi);
  const auto i = static_cast<std::size_t>(a[3][0]);
  ceres::CauchyLoss cauchy(1.0);
  HeldMeasurementPriors robust(s, &cauchy);
  HeldMeasurementPriors squared(s, nullptr);
  robust.FoldUntil(20, a, s.truth.poses, s.truth.landmarks);
  squared.FoldUntil(20, a, s.truth.poses, s.truth.landmarks);
  EXPECT_LT((robust.Mean(i) - s.truth.landmarks[i]).norm(), 0.01);
  EXPECT_GT((squared.Mean(i) - s.truth.landmarks[i]).norm(), 1.0);
}

// A chunk's graph holds the measurements of its free poses and one prior per landmark they see,
// whatever the length of the held past; without the priors, every measurement of those
// landmarks.
TEST(HeldMeasurementPriors, BoundTheChunkGraph) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  const Association a = KnownLabels(s);
  std::vector<Pose> poses = s.truth.poses;
  std::vector<Landmark> landmarks = s.truth.landmarks;
  const std::vector<OdometryIncrement> inc = ScenarioOdometry(s, {});
  const OdometrySpec odometry{&inc, {}, true};
  constexpr std::size_t kHeld = 80;
  HeldMeasurementPriors priors(s, nullptr);
  EXPECT_THROW(FactorGraph(s, odometry, a, nullptr, &poses, &landmarks, kHeld, &priors),
               std::invalid_argument);  // nothing folded yet
  priors.FoldUntil(kHeld, a, poses, landmarks);
  const FactorGraph with_priors(s, odometry, a, nullptr, &poses, &landmarks, kHeld, &priors);
  const FactorGraph without(s, odometry, a, nullptr, &poses, &landmarks, kHeld);
  std::size_t free_measurements = 0;
  std::size_t all_measurements = 0;
  std::vector<bool> seen_free(landmarks.size(), false);
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (int l : a[k]) {
      if (l == kUnassociated) continue;
      ++all_measurements;
      if (k >= kHeld) {
        ++free_measurements;
        seen_free[static_cast<std::size_t>(l)] = true;
      }
    }
  }
  std::size_t expected_priors = 0;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    if (seen_free[i] && priors.Has(i)) ++expected_priors;
  }
  EXPECT_EQ(with_priors.residuals(), free_measurements);
  EXPECT_EQ(with_priors.priors(), expected_priors);
  EXPECT_GT(expected_priors, 0u);
  EXPECT_EQ(without.priors(), 0u);
  // Without the priors: every measurement of the landmarks the free poses see, held or not.
  std::size_t of_seen_landmarks = 0;
  for (const auto& step : a) {
    for (int l : step) {
      if (l != kUnassociated && seen_free[static_cast<std::size_t>(l)]) ++of_seen_landmarks;
    }
  }
  EXPECT_EQ(without.residuals(), of_seen_landmarks);
  EXPECT_GT(without.residuals(), 3 * with_priors.residuals());
  EXPECT_LE(without.residuals(), all_measurements);
}

TEST(HeldMeasurementPriors, RejectsAFoldBeyondTheRun) {
  const datasets::Scenario s = MakeCircleScenario(NoiseFree());
  const Association a = KnownLabels(s);
  HeldMeasurementPriors priors(s, nullptr);
  EXPECT_THROW(priors.FoldUntil(a.size() + 1, a, s.truth.poses, s.truth.landmarks),
               std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference
