#include "datasets/scphd_simulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "datasets/scenario_check.h"
#include "src/core/angles.h"

namespace phdslam::datasets {
namespace {

TEST(ScPhdSim, HasThePapersNoiseDetectionAndClutter) {
  const Scenario s = MakeScPhdSimScenario(ScPhdSimOptions{}, 1);
  EXPECT_EQ(s.name, "scphd-sim");
  EXPECT_EQ(s.motion, MotionKind::kCar);
  EXPECT_DOUBLE_EQ(s.control_noise_cov(0, 0), 4.0);
  EXPECT_NEAR(std::sqrt(s.control_noise_cov(1, 1)), DegToRad(5.0), 1e-15);
  EXPECT_DOUBLE_EQ(s.sensor.noise_cov(0, 0), 1.0);
  EXPECT_NEAR(std::sqrt(s.sensor.noise_cov(1, 1)), DegToRad(2.0), 1e-15);
  EXPECT_DOUBLE_EQ(s.sensor.pd_max, 0.95);
  EXPECT_DOUBLE_EQ(s.sensor.clutter_rate, 5.0);
  EXPECT_NO_THROW(CheckScenario(s, "scphd-sim seed 1"));
}

TEST(ScPhdSim, DrivesTwoLapsOfTheCircle) {
  const ScPhdSimOptions o;
  const Scenario s = MakeScPhdSimScenario(o, 1);
  ASSERT_EQ(s.truth.poses.size(), 838u);
  double path = 0.0;
  for (std::size_t k = 0; k < s.truth.poses.size(); ++k) {
    // The Euler steps of 0.6 m are chords of the 40 m circle.
    EXPECT_NEAR(s.truth.poses[k].head<2>().norm(), 40.0, 1e-9) << "step " << k;
    if (k > 0) path += (s.truth.poses[k] - s.truth.poses[k - 1]).head<2>().norm();
  }
  EXPECT_NEAR(path, 837 * 0.6, 1e-6);
  EXPECT_GT(path, 2.0 * 2.0 * std::numbers::pi * 40.0 - 0.6);
}

TEST(ScPhdSim, MapIsFixedAndMeasurementsChangeWithTheSeed) {
  const ScPhdSimOptions o;
  const Scenario a = MakeScPhdSimScenario(o, 1);
  const Scenario b = MakeScPhdSimScenario(o, 2);
  const Scenario a2 = MakeScPhdSimScenario(o, 1);
  ASSERT_EQ(a.truth.landmarks.size(), 60u);
  EXPECT_EQ(a.truth.landmarks, b.truth.landmarks);
  EXPECT_EQ(a.truth.poses, b.truth.poses);
  for (const Landmark& m : a.truth.landmarks) {
    EXPECT_GE(m.norm(), 20.0);
    EXPECT_LE(m.norm(), 60.0);
  }
  EXPECT_EQ(a.steps[200].data.measurements, a2.steps[200].data.measurements);
  EXPECT_NE(a.steps[200].data.measurements, b.steps[200].data.measurements);
  EXPECT_NE(a.steps[200].data.controls, b.steps[200].data.controls);
}

TEST(ScPhdSim, SeesSeveralLandmarksPerScan) {
  const Scenario s = MakeScPhdSimScenario(ScPhdSimOptions{}, 3);
  double in_view = 0.0;
  for (const Pose& x : s.truth.poses) {
    for (const Landmark& m : s.truth.landmarks) in_view += s.sensor.DetectionProbability(x, m) > 0;
  }
  in_view /= static_cast<double>(s.truth.poses.size());
  EXPECT_GT(in_view, 4.0);
  EXPECT_LT(in_view, 12.0);
}

TEST(ScPhdSim, RejectsBadOptions) {
  ScPhdSimOptions o;
  o.map_outer_radius = 10.0;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
  o = ScPhdSimOptions{};
  o.speed = 0.0;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::datasets
