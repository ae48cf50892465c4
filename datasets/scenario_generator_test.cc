#include "datasets/scenario_generator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>

#include "datasets/scenario_check.h"
#include "src/core/angles.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::datasets {
namespace {

double DistanceToPath(const Vec2& p, const std::vector<Pose>& poses) {
  double best = (p - poses[0].head<2>()).norm();
  for (std::size_t k = 1; k < poses.size(); ++k) {
    const Vec2 a = poses[k - 1].head<2>();
    const Vec2 ab = poses[k].head<2>() - a;
    const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (a + s * ab)).norm());
  }
  return best;
}

int LandmarksInFov(const Scenario& s, std::size_t k) {
  int count = 0;
  for (const Landmark& m : s.truth.landmarks) {
    if (s.sensor.DetectionProbability(s.truth.poses[k], m) > 0.0) ++count;
  }
  return count;
}

TEST(GenerateScenario, DeterministicInOptionsAndSeed) {
  GeneratorOptions o;
  o.steps = 300;
  const Scenario a = GenerateScenario(o, 5);
  const Scenario b = GenerateScenario(o, 5);
  const Scenario c = GenerateScenario(o, 6);
  EXPECT_EQ(a.name, "generated");
  EXPECT_EQ(a.seed, 5u);
  ASSERT_EQ(a.steps.size(), 300u);
  EXPECT_EQ(a.truth.landmarks, b.truth.landmarks);
  EXPECT_EQ(a.truth.poses, b.truth.poses);
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    ASSERT_EQ(a.steps[k].data.measurements, b.steps[k].data.measurements);
    ASSERT_EQ(a.steps[k].data.controls, b.steps[k].data.controls);
    ASSERT_EQ(a.steps[k].origin, b.steps[k].origin);
  }
  EXPECT_NE(a.truth.landmarks, c.truth.landmarks);
  EXPECT_EQ(a.truth.poses, c.truth.poses);  // the trajectory depends on the options only
  EXPECT_NO_THROW(CheckScenario(a, "generated seed 5"));
}

TEST(GenerateScenario, SensorOptionsDoNotMoveTheMap) {
  GeneratorOptions o;
  o.steps = 50;
  const Scenario a = GenerateScenario(o, 3);
  o.clutter_rate = 20.0;
  o.detection_probability = 0.5;
  const Scenario b = GenerateScenario(o, 3);
  EXPECT_EQ(a.truth.landmarks, b.truth.landmarks);
  EXPECT_EQ(b.sensor.clutter_rate, 20.0);
  EXPECT_EQ(b.sensor.pd_max, 0.5);
}

TEST(GenerateScenario, TrajectoryAndLandmarksFollowTheOptions) {
  GeneratorOptions o;
  o.steps = 400;
  o.speed = 2.0;
  o.dt = 0.5;
  o.landmarks = 250;
  o.corridor_half_width = 40.0;
  o.initial_pose = Pose(10.0, -20.0, 0.3);
  const Scenario s = GenerateScenario(o, 11);
  ASSERT_EQ(s.truth.poses.size(), 400u);
  EXPECT_EQ(s.truth.poses[0], o.initial_pose);
  EXPECT_EQ(s.initial_pose, o.initial_pose);
  for (std::size_t k = 1; k < s.truth.poses.size(); ++k) {
    // Chord of an arc of length v dt with turn at most amplitude * dt.
    const double step = (s.truth.poses[k] - s.truth.poses[k - 1]).head<2>().norm();
    ASSERT_NEAR(step, o.speed * o.dt, 1e-4);
    ASSERT_LE(std::abs(s.truth.poses[k](2) - s.truth.poses[k - 1](2)),
              o.turn_amplitude * o.dt + 1e-15);
    ASSERT_EQ(s.steps[k].data.times, (std::vector<double>{static_cast<double>(k - 1) * 0.5,
                                                          static_cast<double>(k) * 0.5}));
  }
  ASSERT_EQ(s.truth.landmarks.size(), 250u);
  const double cell_diagonal = std::sqrt(2.0) * o.corridor_half_width / 32.0;
  for (const Landmark& m : s.truth.landmarks) {
    EXPECT_LE(DistanceToPath(m, s.truth.poses), o.corridor_half_width + cell_diagonal);
  }
}

TEST(GenerateScenario, NoiseFreeScansAreTheVisibleLandmarks) {
  GeneratorOptions o;
  o.steps = 100;
  o.detection_probability = 1.0;
  o.clutter_rate = 0.0;
  o.measurement_noise_cov.setZero();
  o.control_noise_cov.setZero();
  const Scenario s = GenerateScenario(o, 2);
  int total = 0;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    const auto& step = s.steps[k];
    ASSERT_EQ(step.origin.size(), static_cast<std::size_t>(LandmarksInFov(s, k)));
    for (std::size_t j = 0; j < step.origin.size(); ++j) {
      const Landmark& m = s.truth.landmarks[static_cast<std::size_t>(step.origin[j])];
      EXPECT_EQ(step.data.measurements[j], models::PredictMeasurement(s.truth.poses[k], m));
    }
    total += static_cast<int>(step.origin.size());
  }
  EXPECT_GT(total, 0);
}

TEST(GenerateScenario, InvalidOptionsNameTheField) {
  const auto error = [](const GeneratorOptions& o) {
    try {
      (void)GenerateScenario(o, 1);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  GeneratorOptions o;
  o.steps = 0;
  EXPECT_NE(error(o).find("GeneratorOptions.steps"), std::string::npos);
  o = GeneratorOptions();
  o.dt = 0.0;
  EXPECT_NE(error(o).find("GeneratorOptions.dt"), std::string::npos);
  o = GeneratorOptions();
  o.corridor_half_width = -1.0;
  EXPECT_NE(error(o).find("corridor_half_width"), std::string::npos);
  o = GeneratorOptions();
  o.landmarks = -3;
  EXPECT_NE(error(o).find("landmarks"), std::string::npos);
  o = GeneratorOptions();
  o.detection_probability = 1.5;
  EXPECT_NE(error(o).find("GeneratorOptions.detection_probability"), std::string::npos);
  o = GeneratorOptions();
  o.initial_pose(2) = std::nan("");
  EXPECT_NE(error(o).find("initial_pose"), std::string::npos);
  EXPECT_THROW((void)OptionsForLandmarksInView(-1, 100), std::invalid_argument);
  EXPECT_THROW((void)OptionsForLandmarksInView(10, 0), std::invalid_argument);
}

TEST(OptionsForLandmarksInView, MeanCountInFovIsCloseToTheTarget) {
  for (const int target : {10, 40}) {
    const GeneratorOptions o = OptionsForLandmarksInView(target, 1000);
    EXPECT_EQ(o.steps, 1000);
    EXPECT_EQ(o.corridor_half_width, o.fov_range);
    double sum = 0.0;
    double steps = 0.0;
    constexpr int kSeeds = 8;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      const Scenario s = GenerateScenario(o, static_cast<std::uint64_t>(seed));
      for (std::size_t k = 0; k < s.steps.size(); ++k) {
        sum += LandmarksInFov(s, k);
        steps += 1.0;
      }
    }
    const double mean = sum / steps;
    std::cout << "[ info ] target " << target << " in view: " << o.landmarks
              << " landmarks, mean in FOV over " << kSeeds << " seeds " << mean << "\n";
    // The per-step count is about Poisson(target); steps within one seed are strongly
    // correlated (the FOV moves 1 m per 150 m range), so allow 10 % of the target.
    EXPECT_NEAR(mean, target, 0.1 * target);
  }
}

TEST(GenerateScenarioPrefix, SameLandmarksAndFirstStepsAsTheWholeScenario) {
  GeneratorOptions o;
  o.steps = 300;
  const Scenario whole = GenerateScenario(o, 7);
  const Scenario prefix = GenerateScenarioPrefix(o, 7, 40);
  EXPECT_EQ(prefix.truth.landmarks, whole.truth.landmarks);
  ASSERT_EQ(prefix.steps.size(), 40u);
  ASSERT_EQ(prefix.truth.poses.size(), 40u);
  for (std::size_t k = 0; k < prefix.steps.size(); ++k) {
    EXPECT_EQ(prefix.truth.poses[k], whole.truth.poses[k]);
    ASSERT_EQ(prefix.steps[k].data.measurements, whole.steps[k].data.measurements);
    ASSERT_EQ(prefix.steps[k].data.controls, whole.steps[k].data.controls);
    ASSERT_EQ(prefix.steps[k].origin, whole.steps[k].origin);
  }
  EXPECT_THROW(GenerateScenarioPrefix(o, 7, 0), std::invalid_argument);
  EXPECT_THROW(GenerateScenarioPrefix(o, 7, 301), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::datasets
