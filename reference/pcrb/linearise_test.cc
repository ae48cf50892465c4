#include "reference/pcrb/linearise.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "reference/ceres/test_scenario.h"
#include "reference/pcrb/filtering_bound.h"

namespace phdslam::reference::pcrb {
namespace {

using reference::testing::CircleScenarioOptions;
using reference::testing::MakeCircleScenario;

datasets::Scenario Circle(double pd, std::uint64_t seed, double clutter = 0.0) {
  CircleScenarioOptions o;
  o.steps = 60;
  o.landmarks = 10;
  o.detection_probability = pd;
  o.clutter_rate = clutter;
  o.first_step_propagates = true;
  o.seed = seed;
  return MakeCircleScenario(o);
}

PcrbParams With(DetectionModel m) {
  PcrbParams p;
  p.detection_model = m;
  return p;
}

std::string ErrorOf(const datasets::Scenario& s, const PcrbParams& p) {
  try {
    Linearise(s, p, 1, "pcrb");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Linearise, IrfEqualsConditionedAtFullDetectionWithoutClutter) {
  const datasets::Scenario s = Circle(1.0, 4);
  const FilteringBound irf =
      ComputeFilteringBound(Linearise(s, With(DetectionModel::kIrf), 1, "x"));
  const FilteringBound cond =
      ComputeFilteringBound(Linearise(s, With(DetectionModel::kConditioned), 1, "x"));
  for (std::size_t k = 0; k < irf.pose_covs.size(); ++k) {
    EXPECT_LT((irf.pose_covs[k] - cond.pose_covs[k]).cwiseAbs().maxCoeff(),
              1e-12 * std::max(irf.pose_covs[k].norm(), 1e-12))
        << "step " << k;
  }
}

// By Jensen's inequality the seed average of the conditioned bound (the inverse of an
// information that is linear in the detection indicators) is at least the bound of the average
// information, which is the reduction-factor bound: the conditioned bound is the tighter.
TEST(Linearise, SeedAverageOfTheConditionedBoundIsAboveTheIrfBound) {
  const int seeds = 60;
  double conditioned = 0.0;
  double irf = 0.0;
  for (int seed = 1; seed <= seeds; ++seed) {
    const datasets::Scenario s = Circle(0.5, static_cast<std::uint64_t>(seed));
    auto mean_trace = [](const FilteringBound& b) {
      double t = 0.0;
      for (const Mat3& p : b.pose_covs) t += p.topLeftCorner<2, 2>().trace();
      return t / static_cast<double>(b.pose_covs.size());
    };
    conditioned +=
        mean_trace(ComputeFilteringBound(Linearise(s, With(DetectionModel::kConditioned), 1, "x")));
    irf += mean_trace(ComputeFilteringBound(Linearise(s, With(DetectionModel::kIrf), 1, "x")));
  }
  EXPECT_GT(conditioned / seeds, 1.02 * irf / seeds);
}

TEST(Linearise, ClutterLowersTheInformationOfEveryDetection) {
  const datasets::Scenario clean = Circle(1.0, 2);
  const datasets::Scenario cluttered = Circle(1.0, 2, 20.0);
  const LinearisedSlam a = Linearise(clean, With(DetectionModel::kIrf), 1, "x");
  const LinearisedSlam b = Linearise(cluttered, With(DetectionModel::kIrf), 1, "x");
  ASSERT_FALSE(a.steps[5].detections.empty());
  EXPECT_GT(b.steps[5].detections[0].cov(0, 0), a.steps[5].detections[0].cov(0, 0));
}

// The motion Jacobians are those at the true control (recovered from consecutive true poses),
// so the bound does not depend on the odometry noise drawn for the seed.
TEST(Linearise, MotionJacobiansAreAtTheTrueControlsNotTheNoisyOdometry) {
  CircleScenarioOptions o;
  o.steps = 30;
  o.landmarks = 6;
  o.first_step_propagates = true;
  o.noise = false;
  const LinearisedSlam exact = Linearise(MakeCircleScenario(o), PcrbParams{}, 1, "x");
  o.noise = true;
  const LinearisedSlam noisy = Linearise(MakeCircleScenario(o), PcrbParams{}, 1, "x");
  ASSERT_EQ(exact.steps.size(), noisy.steps.size());
  for (std::size_t k = 0; k < exact.steps.size(); ++k) {
    ASSERT_EQ(exact.steps[k].motion.size(), noisy.steps[k].motion.size());
    for (std::size_t b = 0; b < exact.steps[k].motion.size(); ++b) {
      EXPECT_LT((exact.steps[k].motion[b].fx - noisy.steps[k].motion[b].fx).cwiseAbs().maxCoeff(),
                1e-9)
          << "step " << k;
      EXPECT_LT((exact.steps[k].motion[b].fu - noisy.steps[k].motion[b].fu).cwiseAbs().maxCoeff(),
                1e-9)
          << "step " << k;
    }
  }
}

TEST(Linearise, RefusesAScenarioWithoutTruth) {
  datasets::Scenario s = Circle(0.9, 1);
  s.name = "victoria-park";
  s.truth.landmarks.clear();
  const std::string e = ErrorOf(s, PcrbParams{});
  EXPECT_NE(e.find("victoria-park"), std::string::npos) << e;
  EXPECT_NE(e.find("true trajectory and map"), std::string::npos) << e;
}

TEST(Linearise, RefusesNonFiniteOrSingularNoise) {
  datasets::Scenario s = Circle(0.9, 1);
  s.control_noise_cov(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(ErrorOf(s, PcrbParams{}).find("control noise covariance"), std::string::npos);
  s = Circle(0.9, 1);
  s.control_noise_cov(1, 1) = 0.0;
  EXPECT_NE(ErrorOf(s, PcrbParams{}).find("control noise covariance"), std::string::npos);
  s = Circle(0.9, 1);
  s.sensor.noise_cov = Mat2::Zero();
  EXPECT_NE(ErrorOf(s, PcrbParams{}).find("measurement noise covariance"), std::string::npos);
}

TEST(Linearise, RefusesDetectionProbabilityZero) {
  datasets::Scenario s = Circle(0.9, 1);
  s.sensor.pd_max = 0.0;
  const std::string e = ErrorOf(s, PcrbParams{});
  EXPECT_NE(e.find("detection_probability"), std::string::npos) << e;
  EXPECT_NE(e.find("circle"), std::string::npos) << e;
}

TEST(Linearise, ConditionedModelNeedsOriginLabels) {
  datasets::Scenario s = Circle(0.9, 1);
  for (datasets::ScenarioStep& step : s.steps) step.origin.clear();
  EXPECT_NE(ErrorOf(s, With(DetectionModel::kConditioned)).find("detection_model=irf"),
            std::string::npos);
  EXPECT_NO_THROW(Linearise(s, With(DetectionModel::kIrf), 1, "pcrb"));
}

}  // namespace
}  // namespace phdslam::reference::pcrb
