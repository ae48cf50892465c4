#include "datasets/glmb_simulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "datasets/scenario_check.h"
#include "src/core/angles.h"

namespace phdslam::datasets {
namespace {

// Landmark detections (origin >= 0) of a step.
std::vector<Measurement> Detections(const ScenarioStep& step) {
  std::vector<Measurement> out;
  for (std::size_t j = 0; j < step.origin.size(); ++j) {
    if (step.origin[j] >= 0) out.push_back(step.data.measurements[j]);
  }
  return out;
}

int InView(const Scenario& s, std::size_t k) {
  int n = 0;
  for (const Landmark& m : s.truth.landmarks)
    n += s.sensor.DetectionProbability(s.truth.poses[k], m) > 0.0;
  return n;
}

TEST(GlmbSim, HasThePapersSensorNoiseAndClutterIntensity) {
  const Scenario s = MakeGlmbSimScenario(GlmbSimOptions{}, 1);
  EXPECT_EQ(s.name, "glmb-sim");
  EXPECT_EQ(s.motion, MotionKind::kCar);
  EXPECT_DOUBLE_EQ(s.car.encoder_offset_h, 0.0);
  EXPECT_NEAR(std::sqrt(s.control_noise_cov(0, 0)), 0.1, 1e-15);
  EXPECT_NEAR(std::sqrt(s.control_noise_cov(1, 1)), DegToRad(2.0), 1e-15);
  EXPECT_NEAR(std::sqrt(s.sensor.noise_cov(0, 0)), 0.05, 1e-15);
  EXPECT_NEAR(std::sqrt(s.sensor.noise_cov(1, 1)), DegToRad(0.5), 1e-15);
  EXPECT_DOUBLE_EQ(s.sensor.pd_max, 0.7);
  EXPECT_DOUBLE_EQ(s.sensor.fov_range, 3.0);
  EXPECT_DOUBLE_EQ(s.sensor.fov_half_angle, std::numbers::pi);
  EXPECT_DOUBLE_EQ(s.sensor.clutter_rate, 1.0);
  EXPECT_EQ(s.sensor.clutter_space, models::ClutterSpace::kRangeBearingBox);
  EXPECT_NEAR(s.sensor.ClutterIntensity(), 1.0 / (6.0 * std::numbers::pi), 1e-15);
  EXPECT_EQ(s.initial_pose, s.truth.poses[0]);
  EXPECT_NO_THROW(CheckScenario(s, "glmb-sim seed 1"));
}

TEST(GlmbSim, DrivesAClosedLoopAtOneMetrePerSecondAndRevisitsIt) {
  const GlmbSimOptions o;
  const Scenario s = MakeGlmbSimScenario(o, 1);
  ASSERT_EQ(s.truth.poses.size(), 175u);
  for (std::size_t k = 1; k < s.truth.poses.size(); ++k) {
    EXPECT_NEAR((s.truth.poses[k] - s.truth.poses[k - 1]).head<2>().norm(), 0.2, 1e-12);
  }
  // The loop closes after 124 steps and steps 124-174 drive its first 51 steps again.
  for (std::size_t k = 0; k + kGlmbSimLoopSteps < s.truth.poses.size(); ++k) {
    const Pose& a = s.truth.poses[k];
    const Pose& b = s.truth.poses[k + kGlmbSimLoopSteps];
    EXPECT_NEAR((a - b).head<2>().norm(), 0.0, 1e-9) << "step " << k;
    EXPECT_NEAR(WrapAngle(a(2) - b(2)), 0.0, 1e-9) << "step " << k;
  }
  // A loop, not a line: the far side lies several metres from the start.
  double farthest = 0.0;
  for (const Pose& x : s.truth.poses) farthest = std::max(farthest, x.head<2>().norm());
  EXPECT_GT(farthest, 6.0);
  EXPECT_LT(farthest, 12.0);
}

TEST(GlmbSim, HasTwentyThreeFixedLandmarksAndSeesOnlyLocalOnes) {
  const Scenario a = MakeGlmbSimScenario(GlmbSimOptions{}, 1);
  const Scenario b = MakeGlmbSimScenario(GlmbSimOptions{}, 2);
  ASSERT_EQ(a.truth.landmarks.size(), 23u);
  EXPECT_EQ(a.truth.landmarks, b.truth.landmarks);
  EXPECT_EQ(a.truth.poses, b.truth.poses);
  double mean_in_view = 0.0;
  int max_in_view = 0;
  for (std::size_t k = 0; k < a.truth.poses.size(); ++k) {
    const int n = InView(a, k);
    EXPECT_GE(n, 1) << "step " << k;
    max_in_view = std::max(max_in_view, n);
    mean_in_view += n;
  }
  mean_in_view /= static_cast<double>(a.truth.poses.size());
  EXPECT_GT(mean_in_view, 3.0);
  EXPECT_LT(max_in_view, 23 / 2);  // a 3 m disc never holds half the map
}

TEST(GlmbSim, DetectsAboutPdOfTheLandmarksInView) {
  GlmbSimOptions o;
  o.clutter_rate = 0.0;
  double detected = 0.0;
  double in_view = 0.0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Scenario s = MakeGlmbSimScenario(o, seed);
    for (std::size_t k = 0; k < s.steps.size(); ++k) {
      in_view += InView(s, k);
      detected += static_cast<double>(Detections(s.steps[k]).size());
      EXPECT_EQ(s.steps[k].origin.size(), Detections(s.steps[k]).size());  // no clutter at all
    }
  }
  // Binomial: sd of the ratio about sqrt(0.21 / in_view) < 0.004 for in_view > 15000.
  ASSERT_GT(in_view, 15000.0);
  EXPECT_NEAR(detected / in_view, 0.7, 0.015);
}

TEST(GlmbSim, ClutterIsPoissonWithTheRequestedMeanAndUniformInRangeBearing) {
  GlmbSimOptions o;
  o.clutter_rate = 5.0;
  double count = 0.0;
  double scans = 0.0;
  double sum_r = 0.0;
  double sum_b = 0.0;
  double sum_b2 = 0.0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Scenario s = MakeGlmbSimScenario(o, seed);
    for (const ScenarioStep& step : s.steps) {
      scans += 1.0;
      for (std::size_t j = 0; j < step.origin.size(); ++j) {
        if (step.origin[j] != kClutter) continue;
        const Measurement& z = step.data.measurements[j];
        ASSERT_GE(z(0), 0.0);
        ASSERT_LT(z(0), 3.0);
        count += 1.0;
        sum_r += z(0);
        sum_b += z(1);
        sum_b2 += z(1) * z(1);
      }
    }
  }
  // 3500 scans: the mean count has sd sqrt(5 / 3500) = 0.038 (not thinned by pD).
  EXPECT_NEAR(count / scans, 5.0, 0.15);
  EXPECT_NEAR(sum_r / count, 1.5, 0.05);  // uniform on [0, 3): sd of the mean 0.015
  EXPECT_NEAR(sum_b / count, 0.0, 0.1);   // uniform on [-pi, pi): sd of the mean 0.014
  EXPECT_NEAR(sum_b2 / count, std::numbers::pi * std::numbers::pi / 3.0, 0.15);
}

TEST(GlmbSim, IsDeterministicAndDrawsFreshDataPerSeedByDefault) {
  const GlmbSimOptions o;
  const Scenario a = MakeGlmbSimScenario(o, 7);
  const Scenario a2 = MakeGlmbSimScenario(o, 7);
  const Scenario b = MakeGlmbSimScenario(o, 8);
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(a.steps[k].data.measurements, a2.steps[k].data.measurements);
    EXPECT_EQ(a.steps[k].data.controls, a2.steps[k].data.controls);
    EXPECT_EQ(a.steps[k].origin, a2.steps[k].origin);
  }
  EXPECT_NE(a.steps[100].data.controls, b.steps[100].data.controls);
  EXPECT_NE(a.steps[100].data.measurements, b.steps[100].data.measurements);
}

TEST(GlmbSim, SingleRealisationGivesEverySeedTheSameData) {
  GlmbSimOptions o;
  o.data_protocol = GlmbDataProtocol::kSingleRealisation;
  o.data_seed = 3;
  const Scenario a = MakeGlmbSimScenario(o, 1);
  const Scenario b = MakeGlmbSimScenario(o, 2);
  GlmbSimOptions per_seed;
  const Scenario c = MakeGlmbSimScenario(per_seed, 3);
  EXPECT_EQ(a.seed, 1u);  // the filters' streams still follow the Monte Carlo seed
  EXPECT_EQ(b.seed, 2u);
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(a.steps[k].data.measurements, b.steps[k].data.measurements);
    EXPECT_EQ(a.steps[k].data.controls, b.steps[k].data.controls);
    // ... and that data is per-seed run data_seed.
    EXPECT_EQ(a.steps[k].data.measurements, c.steps[k].data.measurements);
  }
}

TEST(GlmbSim, ClutterIsAnOverlayOnTheSameDetectionsAndOdometry) {
  GlmbSimOptions low;
  low.clutter_rate = 1.0;
  GlmbSimOptions high;
  high.clutter_rate = 15.0;
  const Scenario a = MakeGlmbSimScenario(low, 4);
  const Scenario b = MakeGlmbSimScenario(high, 4);
  double clutter_b = 0.0;
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(Detections(a.steps[k]), Detections(b.steps[k])) << "step " << k;
    EXPECT_EQ(a.steps[k].data.controls, b.steps[k].data.controls) << "step " << k;
    clutter_b += static_cast<double>(b.steps[k].origin.size() - Detections(b.steps[k]).size());
  }
  EXPECT_NEAR(clutter_b / static_cast<double>(b.steps.size()), 15.0, 1.5);  // sd 0.29
}

TEST(GlmbSim, RejectsBadOptions) {
  GlmbSimOptions o;
  o.dt = 0.0;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
  o = GlmbSimOptions{};
  o.data_seed = -1;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
  o = GlmbSimOptions{};
  o.detection_probability = 1.5;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
  o = GlmbSimOptions{};
  o.landmark_offset = -1.0;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::datasets
