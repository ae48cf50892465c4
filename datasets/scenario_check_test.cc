#include "datasets/scenario_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace phdslam::datasets {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

/// Four steps at t = 0, 1, 2, 3 with two landmarks and a few measurements each.
Scenario SmallScenario() {
  Scenario s;
  s.name = "small";
  s.truth.landmarks = {Landmark(10.0, 0.0), Landmark(0.0, 10.0)};
  for (int k = 0; k < 4; ++k) {
    ScenarioStep step;
    if (k == 0) {
      step.data.times = {0.0};
    } else {
      step.data.times = {k - 1.0, static_cast<double>(k)};
      step.data.controls = {Control(1.0, 0.01)};
    }
    step.data.measurements = {Measurement(10.0, 0.1), Measurement(5.0, -0.2),
                              Measurement(7.0, 0.3)};
    step.origin = {0, kClutter, 1};
    s.steps.push_back(step);
    s.truth.poses.push_back(Pose(k, 0.0, 0.0));
  }
  return s;
}

std::string ErrorOf(const Scenario& s) {
  try {
    CheckScenario(s, "unit-source");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(CheckScenario, AcceptsAValidScenario) { EXPECT_EQ(ErrorOf(SmallScenario()), ""); }

TEST(CheckScenario, NanMeasurementNamesSourceStepAndIndex) {
  Scenario s = SmallScenario();
  s.steps[2].data.measurements[1](0) = kNan;
  EXPECT_EQ(ErrorOf(s), "unit-source: step 2: measurement 1: range is nan");
  s = SmallScenario();
  s.steps[3].data.measurements[2](1) = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ErrorOf(s), "unit-source: step 3: measurement 2: bearing is inf");
}

TEST(CheckScenario, NanControlAndTime) {
  Scenario s = SmallScenario();
  s.steps[1].data.controls[0](1) = kNan;
  EXPECT_EQ(ErrorOf(s), "unit-source: step 1: control 0: component 1 is nan");
  s = SmallScenario();
  s.steps[2].data.times[1] = kNan;
  EXPECT_EQ(ErrorOf(s), "unit-source: step 2: times[1] is nan");
}

TEST(CheckScenario, TimesMustNotDecrease) {
  Scenario s = SmallScenario();
  s.steps[2].data.times = {1.0, 0.5};
  std::string message = ErrorOf(s);
  EXPECT_NE(message.find("unit-source: step 2: times[1] = 0.5"), std::string::npos) << message;
  EXPECT_NE(message.find("non-decreasing"), std::string::npos) << message;
  s = SmallScenario();
  s.steps[3].data.times = {1.5, 2.5};  // starts before step 2 ended (t = 2)
  message = ErrorOf(s);
  EXPECT_NE(message.find("step 3: times[0] = 1.5"), std::string::npos) << message;
  s = SmallScenario();
  s.steps[1].data.times = {};
  EXPECT_NE(ErrorOf(s).find("step 1: times is empty"), std::string::npos);
}

TEST(CheckScenario, ControlCountMustMatchTimes) {
  Scenario s = SmallScenario();
  s.steps[0].data.controls = {Control(1.0, 0.0)};
  EXPECT_EQ(ErrorOf(s), "unit-source: step 0: controls.size() is 1, expected times.size() - 1 = 0");
}

TEST(CheckScenario, OriginSizeAndValues) {
  Scenario s = SmallScenario();
  s.steps[1].origin.pop_back();
  EXPECT_NE(ErrorOf(s).find("step 1: origin.size() is 2"), std::string::npos);
  s = SmallScenario();
  s.steps[1].origin.clear();  // unknown origins are allowed
  EXPECT_EQ(ErrorOf(s), "");
  s = SmallScenario();
  s.steps[2].origin[2] = 2;  // only two landmarks
  EXPECT_NE(ErrorOf(s).find("step 2: origin[2] is 2"), std::string::npos);
  s.steps[2].origin[2] = -3;
  EXPECT_NE(ErrorOf(s).find("step 2: origin[2] is -3"), std::string::npos);
  s.steps[2].origin[2] = kUnknownOrigin;  // a real detection of an unidentified landmark
  EXPECT_EQ(ErrorOf(s), "");
}

TEST(CheckScenario, TruthAndParameters) {
  Scenario s = SmallScenario();
  s.truth.poses[3](2) = kNan;
  EXPECT_EQ(ErrorOf(s), "unit-source: truth: step 3: pose[2] is nan");
  s = SmallScenario();
  s.truth.poses.pop_back();
  EXPECT_NE(ErrorOf(s).find("truth: poses.size() is 3"), std::string::npos);
  s = SmallScenario();
  s.truth.landmarks[1](0) = kNan;
  EXPECT_EQ(ErrorOf(s), "unit-source: truth: landmark 1: position[0] is nan");
  s = SmallScenario();
  s.truth.gps.push_back({kNan, Vec2::Zero()});
  EXPECT_EQ(ErrorOf(s), "unit-source: truth: gps fix 0: t is nan");
  s = SmallScenario();
  s.initial_pose(1) = kNan;
  EXPECT_EQ(ErrorOf(s), "unit-source: parameters: initial_pose[1] is nan");
  s = SmallScenario();
  s.control_noise_cov(0, 1) = kNan;
  EXPECT_EQ(ErrorOf(s), "unit-source: parameters: control_noise_cov(0, 1) is nan");
  s = SmallScenario();
  s.sensor.fov_range = kNan;
  EXPECT_NE(ErrorOf(s).find("parameters: sensor.fov_range must be finite and > 0, got nan"),
            std::string::npos);
  s = SmallScenario();
  s.sensor.pd_max = 1.2;
  EXPECT_NE(ErrorOf(s).find("sensor.pd_max must be in [0, 1], got 1.2"), std::string::npos);
  s = SmallScenario();
  s.motion = MotionKind::kCar;
  s.car.wheelbase_l = 0.0;
  EXPECT_NE(ErrorOf(s).find("car.wheelbase_l"), std::string::npos);
}

}  // namespace
}  // namespace phdslam::datasets
