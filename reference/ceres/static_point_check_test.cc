#include "reference/ceres/static_point_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "reference/ceres/batch_smoother.h"
#include "reference/ceres/fixed_lag_smoother.h"
#include "reference/ceres/test_scenario.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

const Mat2 kR = Vec2(0.01, 1e-4).asDiagonal();  // range sigma 0.1 m, bearing sigma 0.01 rad

OdometryIncrement Increment(const Pose& delta, const Vec3& std) {
  OdometryIncrement inc;
  inc.propagated = true;
  inc.delta = delta;
  inc.covariance = std.cwiseAbs2().asDiagonal();
  return inc;
}

TEST(StaticPointChi2, AStaticPointSeenAfterExactOdometryAgreesWithItsFirstDetection) {
  const Pose x0(1.0, 2.0, 0.3);
  const Landmark m(4.0, 5.0);
  StaticPointAnchor anchor = AnchorAt(models::PredictMeasurement(x0, m), kR);
  Pose x = x0;
  for (int k = 0; k < 5; ++k) {
    const OdometryIncrement inc = Increment(Pose(0.4, 0.05, 0.1), Vec3(0.01, 0.01, 0.01));
    AdvanceAnchor(inc, &anchor);
    x = ComposeRelative(x, inc.delta);
  }
  EXPECT_LT(StaticPointChi2(anchor, models::PredictMeasurement(x, m), kR), 1e-12);
  // The odometry's uncertainty has entered the anchor's pose.
  EXPECT_GT(anchor.relative_cov(2, 2), 4e-4);
}

TEST(StaticPointChi2, APointThatMovesWhileTheVehicleStandsStillFails) {
  const Pose x(0.0, 0.0, 0.0);
  StaticPointAnchor anchor = AnchorAt(models::PredictMeasurement(x, Landmark(3.0, 0.0)), kR);
  // Ten steps standing still, the heading known to 0.01 rad per step (0.032 rad after ten).
  for (int k = 0; k < 10; ++k) {
    AdvanceAnchor(Increment(Pose::Zero(), Vec3(0.005, 0.005, 0.01)), &anchor);
  }
  // 0.5 m sideways at 3 m is 0.17 rad: five times what the odometry allows.
  EXPECT_GT(StaticPointChi2(anchor, models::PredictMeasurement(x, Landmark(3.0, 0.5)), kR), 13.8);
  // 5 cm sideways is within it.
  EXPECT_LT(StaticPointChi2(anchor, models::PredictMeasurement(x, Landmark(3.0, 0.05)), kR), 13.8);
}

/// The detection of the point (3, y) from a vehicle standing at the origin facing +x.
Measurement SidewaysPoint(double y) { return models::PredictMeasurement(Pose::Zero(), {3.0, y}); }

/// A track started at the point (3, 0), the vehicle standing still for `steps` steps with a
/// heading noise of 0.002 rad per step.
StaticPointTrack StandingTrack(int steps) {
  StaticPointTrack t;
  t.first = AnchorAt(SidewaysPoint(0.0), kR);
  t.latest = t.first;
  for (int k = 0; k < steps; ++k) {
    AdvanceTrack(Increment(Pose::Zero(), Vec3(0.005, 0.005, 0.002)), &t);
  }
  return t;
}

// A point moving 10 cm sideways per detection (within the check of the previous one, beyond
// that of the first after a few): with one failure required it is a moving object at the first
// detection beyond the first one's check, with three two detections later.
TEST(StaticPointCheck, ConsecutiveFailuresDelayTheVerdictOnAMovingPoint) {
  const auto first_moving = [](int required) {
    StaticPointTrack t = StandingTrack(1);
    const StaticPointOptions o{13.8, 0.2, required};
    for (int n = 1; n <= 20; ++n) {
      AdvanceTrack(Increment(Pose::Zero(), Vec3(0.005, 0.005, 0.002)), &t);
      if (MovingAfter(SidewaysPoint(0.1 * n), kR, o, &t)) return n;
    }
    return 0;
  };
  const int one = first_moving(1);
  ASSERT_GT(one, 1);
  EXPECT_EQ(first_moving(3), one + 2);
}

// A static point whose detections stray once (two detections off to one side, then back): one
// failure required deletes it, two do not, since the detection back at the point resets the
// count.
TEST(StaticPointCheck, AnExcursionOfOneDetectionIsNotMotionWithTwoRequired) {
  const auto moving_anywhere = [](int required) {
    StaticPointTrack t = StandingTrack(3);
    const StaticPointOptions o{13.8, 0.2, required};
    bool moving = false;
    for (double y : {0.0, 0.1, 0.2, 0.0, 0.0})
      moving = moving || MovingAfter(SidewaysPoint(y), kR, o, &t);
    return moving;
  };
  // 0.2 m at 3 m is beyond the first detection's check, 0.1 m within the latest's.
  const StaticPointTrack probe = StandingTrack(3);
  EXPECT_GT(StaticPointChi2(probe.first, SidewaysPoint(0.2), kR), 13.8);
  EXPECT_LT(StaticPointChi2(probe.first, SidewaysPoint(0.1), kR), 13.8);
  StaticPointTrack at_01 = probe;
  at_01.latest = AnchorAt(SidewaysPoint(0.1), kR);
  EXPECT_LT(StaticPointChi2(at_01.latest, SidewaysPoint(0.2), kR), 13.8);
  EXPECT_TRUE(moving_anywhere(1));
  EXPECT_FALSE(moving_anywhere(2));
}

constexpr int kStaticSteps = 5;

/// A vehicle standing still for `steps` 1 s steps, facing +x, that sees a static landmark at
/// (4, 1) in the first and last kStaticSteps steps and in between only a point moving sideways
/// across its view at 3 m (5 cm per step), each detected at every step without noise (as a
/// robot that sees only another robot pass between two sightings of the map). The odometry is
/// exact (zero controls) with a heading noise of 0.01 rad per step in the model.
datasets::Scenario StandingVehicleWithAMovingPoint(int steps) {
  datasets::Scenario s;
  s.name = "standing-vehicle";
  s.motion = datasets::MotionKind::kVelocity;
  s.control_noise_cov = Vec2(1e-4, 1e-4).asDiagonal();
  s.sensor.fov_range = 10.0;
  s.sensor.fov_half_angle = 1.2;
  s.sensor.noise_cov = kR;
  s.sensor.pd_max = 0.95;
  s.sensor.clutter_rate = 0.0;
  s.initial_pose = Pose::Zero();
  s.truth.landmarks = {Landmark(4.0, 1.0)};
  for (int k = 0; k < steps; ++k) {
    datasets::ScenarioStep step;
    if (k == 0) {
      step.data.times = {0.0};
    } else {
      step.data.times = {k - 1.0, static_cast<double>(k)};
      step.data.controls = {Control(0.0, 0.0)};
    }
    s.truth.poses.push_back(Pose::Zero());
    if (k < kStaticSteps || k >= steps - kStaticSteps) {
      step.data.measurements.push_back(
          models::PredictMeasurement(Pose::Zero(), Landmark(4.0, 1.0)));
      step.origin.push_back(0);
    } else {
      const Landmark moving(3.0, -1.0 + 0.05 * (k - kStaticSteps));
      step.data.measurements.push_back(models::PredictMeasurement(Pose::Zero(), moving));
      step.origin.push_back(datasets::kClutter);
    }
    s.steps.push_back(std::move(step));
  }
  return s;
}

/// The largest position (m) or heading (rad) error of the estimated poses: the vehicle stands
/// at the origin facing +x throughout.
double LargestPoseError(const datasets::BatchResult& r) {
  double e = 0.0;
  for (const Pose& x : r.poses) e = std::max({e, x.head<2>().norm(), std::abs(x(2))});
  return e;
}

SmootherOptions OwnIncrementalAssociation(double static_point_chi2) {
  SmootherOptions o;
  o.association = AssociationMode::kUnknown;
  o.initialisation = SmootherInitialisation::kIncremental;
  o.incremental_chunk_steps = 5;
  o.incremental_static_point_chi2 = static_point_chi2;
  o.compute_covariances = false;
  // The static landmark is out of sight (occluded) for 40 of the 50 steps.
  o.min_detection_ratio = 0.1;
  return o;
}

TEST(StaticPointCheck, AMovingPointDetectedRepeatedlyYieldsNoLandmarkAndAStaticOneDoes) {
  const datasets::Scenario s = StandingVehicleWithAMovingPoint(50);
  BatchSmoother checked(OwnIncrementalAssociation(13.8));
  const datasets::BatchResult r = checked.Solve(s);
  EXPECT_GT(checked.report().moving_landmarks, 0);
  ASSERT_EQ(r.map.means.size(), 1u);
  EXPECT_LT((r.map.means[0] - Landmark(4.0, 1.0)).norm(), 0.05);
  EXPECT_LT(LargestPoseError(r), 0.05);
  // Without the check the moving point's detections are mapped: the vehicle is turned to hold the
  // point still, and the static landmark is pulled away from its place.
  BatchSmoother unchecked(OwnIncrementalAssociation(0.0));
  const datasets::BatchResult u = unchecked.Solve(s);
  EXPECT_EQ(unchecked.report().moving_landmarks, 0);
  EXPECT_GT(LargestPoseError(u), 0.2);
  for (const Landmark& m : u.map.means) EXPECT_GT((m - Landmark(4.0, 1.0)).norm(), 0.3);
}

TEST(StaticPointCheck, MapsEveryLandmarkOfAStaticWorld) {
  // The circle of 20 landmarks with clutter (5 per scan), 100 steps: every landmark is static,
  // so the check may delete clutter-born landmarks only.
  testing::CircleScenarioOptions c;
  c.clutter_rate = 5.0;
  const datasets::Scenario s = testing::MakeCircleScenario(c);
  SmootherOptions o = OwnIncrementalAssociation(13.8);
  o.min_detection_ratio = 0.3;
  BatchSmoother smoother(o);
  const datasets::BatchResult r = smoother.Solve(s);
  int near_truth = 0;
  for (const Landmark& m : s.truth.landmarks) {
    for (const Landmark& e : r.map.means) near_truth += (e - m).norm() < 1.0;
  }
  EXPECT_EQ(near_truth, 20);
  EXPECT_LE(r.map.means.size(), 21u);
}

/// The fixed-lag smoother's own association on `s` with the moving-object test at `chi2`.
struct WindowOutcome {
  double largest_pose_error = 0.0;  ///< of the newest pose after each step (a filtered estimate)
  double last_pose_error = 0.0;
  filters::MapEstimate map;
  WindowReport report;
};

WindowOutcome RunOwnWindow(const datasets::Scenario& s, double chi2) {
  WindowParams p;
  p.known_association = false;
  p.static_point_chi2 = chi2;
  FixedLagSmoother window(s.PublicContext(), p, {}, s.steps.size());
  WindowOutcome out;
  for (const datasets::ScenarioStep& step : s.steps) {
    const Pose x = window.Step(step.data).pose;
    out.last_pose_error = std::max(x.head<2>().norm(), std::abs(x(2)));
    out.largest_pose_error = std::max(out.largest_pose_error, out.last_pose_error);
  }
  out.map = window.Map();
  out.report = window.report();
  return out;
}

TEST(StaticPointCheck, TheWindowCountsAPassingObjectAsClutter) {
  const datasets::Scenario s = StandingVehicleWithAMovingPoint(50);
  const WindowOutcome checked = RunOwnWindow(s, 13.8);
  EXPECT_GT(checked.report.moving_landmarks, 0);
  ASSERT_EQ(checked.map.means.size(), 1u);
  EXPECT_LT((checked.map.means[0] - Landmark(4.0, 1.0)).norm(), 0.05);
  // The object's first few detections, before they betray its motion, turn the newest pose by
  // less than 0.1 rad; once it is found moving, the window returns to the truth.
  EXPECT_LT(checked.largest_pose_error, 0.1);
  EXPECT_LT(checked.last_pose_error, 0.01);
  // Without the test the passing point is confirmed as a landmark and turns the vehicle for good.
  const WindowOutcome unchecked = RunOwnWindow(s, 0.0);
  EXPECT_EQ(unchecked.report.moving_landmarks, 0);
  EXPECT_GT(unchecked.last_pose_error, 0.3);
  EXPECT_GT(unchecked.map.means.size(), 1u);
}

TEST(StaticPointCheck, TheWindowKeepsEveryLandmarkOfAStaticWorld) {
  testing::CircleScenarioOptions c;
  c.clutter_rate = 5.0;
  const datasets::Scenario s = testing::MakeCircleScenario(c);
  const WindowOutcome checked = RunOwnWindow(s, 13.8);
  const WindowOutcome unchecked = RunOwnWindow(s, 0.0);
  const auto near_truth = [&](const filters::MapEstimate& map) {
    int n = 0;
    for (const Landmark& m : s.truth.landmarks) {
      for (const Landmark& e : map.means) n += (e - m).norm() < 1.0;
    }
    return n;
  };
  EXPECT_EQ(near_truth(checked.map), near_truth(unchecked.map));
  EXPECT_GE(near_truth(checked.map), 18);
}

TEST(StaticPointCheck, TheWindowRejectsNonsenseSettingsNamingThem) {
  WindowParams p;
  p.static_point_chi2 = -1.0;
  EXPECT_THROW(p.Validate(), std::invalid_argument);
  p.static_point_chi2 = 13.8;
  p.static_point_failures = 0;
  try {
    p.Validate();
    FAIL() << "static_point_failures = 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("static_point_failures"), std::string::npos);
  }
}

TEST(StaticPointCheck, RejectsANegativeThreshold) {
  SmootherOptions o = OwnIncrementalAssociation(-1.0);
  EXPECT_THROW(BatchSmoother{o}, std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference
