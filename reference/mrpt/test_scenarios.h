// Small synthetic scenarios for the tests of the MRPT baselines: landmarks on a circle, a robot
// driving a smaller concentric circle with the velocity motion model, and measurements generated
// the way the paper's synthetic scenario generates them (docs/algorithms/models.md section 4.1):
// visible landmarks in index order, then Poisson clutter uniform in (r, phi), N(0, R) noise and pD
// thinning on every entry, wrapped bearings, odometry = true control + N(0, Q_u). Test-only.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/angles.h"
#include "src/core/random.h"
#include "src/core/types.h"
#include "src/filters/estimator.h"
#include "src/models/range_bearing_model.h"
#include "src/models/velocity_motion_model.h"

namespace phdslam::reference::testing {

struct CircleScenarioOptions {
  int landmarks = 20;
  double landmark_radius = 30.0;  ///< m, landmarks on this circle around the origin
  double speed = 1.5;             ///< m/s; the robot circles the origin at radius speed / turn_rate
  double turn_rate = 0.1;         ///< rad/s
  int steps = 150;                ///< dt = 1 s
  double detection_probability = 1.0;
  double clutter_rate = 0.0;
  double fov_range = 40.0;
  double fov_half_angle = DegToRad(90.0);
  Mat2 measurement_noise_cov = Vec2(0.1 * 0.1, DegToRad(0.5) * DegToRad(0.5)).asDiagonal();
  Mat2 control_noise_cov = Vec2(0.05 * 0.05, DegToRad(1.0) * DegToRad(1.0)).asDiagonal();
};

inline datasets::Scenario MakeCircleScenario(const CircleScenarioOptions& o, std::uint64_t seed) {
  RandomStream rng(DeriveSeed(HashName("mrpt-baselines-test-circle"), seed));
  datasets::Scenario s;
  s.name = "circle";
  s.seed = seed;
  s.motion = datasets::MotionKind::kVelocity;
  s.control_noise_cov = o.control_noise_cov;
  s.sensor.fov_range = o.fov_range;
  s.sensor.fov_half_angle = o.fov_half_angle;
  s.sensor.range_buffer = 5.0;
  s.sensor.angle_buffer = DegToRad(10.0);
  s.sensor.pd_max = o.detection_probability;
  s.sensor.pd_nominal = o.detection_probability;
  s.sensor.noise_cov = o.measurement_noise_cov;
  s.sensor.clutter_rate = o.clutter_rate;
  for (int i = 0; i < o.landmarks; ++i) {
    const double a = 2.0 * std::numbers::pi * i / o.landmarks;
    s.truth.landmarks.emplace_back(o.landmark_radius * std::cos(a),
                                   o.landmark_radius * std::sin(a));
  }
  const double robot_radius = o.speed / o.turn_rate;
  s.initial_pose = Pose(robot_radius, 0.0, std::numbers::pi / 2.0);
  const Control u_true(o.speed, o.turn_rate);
  const models::VelocityMotionModel motion;
  const double sr = std::sqrt(o.measurement_noise_cov(0, 0));
  const double sb = std::sqrt(o.measurement_noise_cov(1, 1));
  const double sv = std::sqrt(o.control_noise_cov(0, 0));
  const double sw = std::sqrt(o.control_noise_cov(1, 1));
  Pose x = s.initial_pose;
  Control odometry_prev = Control::Zero();
  for (int k = 0; k < o.steps; ++k) {
    datasets::ScenarioStep step;
    if (k > 0) {
      x = motion.Predict(x, u_true, 1.0);
      step.data.times = {k - 1.0, static_cast<double>(k)};
      step.data.controls = {odometry_prev};
    } else {
      step.data.times = {0.0};
    }
    std::vector<Measurement> clean;
    std::vector<int> origin;
    for (int i = 0; i < o.landmarks; ++i) {
      const Landmark& m = s.truth.landmarks[static_cast<std::size_t>(i)];
      if (s.sensor.DetectionProbability(x, m) <= 0.0) continue;
      clean.push_back(models::PredictMeasurement(x, m));
      origin.push_back(i);
    }
    const int n_clutter = rng.Poisson(o.clutter_rate);
    for (int c = 0; c < n_clutter; ++c) {
      const double r = rng.Uniform(0.0, o.fov_range);
      const double b = rng.Uniform(-o.fov_half_angle, o.fov_half_angle);
      clean.emplace_back(r, b);
      origin.push_back(datasets::kClutter);
    }
    for (std::size_t j = 0; j < clean.size(); ++j) {
      const Measurement z(clean[j](0) + sr * rng.Normal(), clean[j](1) + sb * rng.Normal());
      if (rng.Uniform() >= o.detection_probability) continue;
      step.data.measurements.emplace_back(z(0), WrapAngle(z(1)));
      step.origin.push_back(origin[j]);
    }
    odometry_prev = u_true + Control(sv * rng.Normal(), sw * rng.Normal());
    s.truth.poses.push_back(x);
    s.steps.push_back(std::move(step));
  }
  return s;
}

/// Runs an online estimator over the whole scenario and returns its pose estimates.
inline std::vector<Pose> RunOnline(filters::OnlineEstimator& estimator,
                                   const datasets::Scenario& s) {
  std::vector<Pose> poses;
  for (const datasets::ScenarioStep& step : s.steps)
    poses.push_back(estimator.Step(step.data).pose);
  return poses;
}

/// Position RMSE over all steps (docs/algorithms/metrics.md section 1.2).
inline double PositionRmse(const datasets::Scenario& s, const std::vector<Pose>& poses) {
  double sum = 0.0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    sum += (poses[k].head<2>() - s.truth.poses[k].head<2>()).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(poses.size()));
}

/// Number of map points within `radius` of no true landmark (spurious points).
inline int CountFarFromTruth(const filters::MapEstimate& map, const datasets::Scenario& s,
                             double radius) {
  int n = 0;
  for (const Landmark& m : map.means) {
    bool near = false;
    for (const Landmark& t : s.truth.landmarks) near = near || (m - t).norm() <= radius;
    if (!near) ++n;
  }
  return n;
}

/// Number of true landmarks with at least one map point within `radius`.
inline int CountCoveredTruth(const filters::MapEstimate& map, const datasets::Scenario& s,
                             double radius) {
  int n = 0;
  for (const Landmark& t : s.truth.landmarks) {
    bool hit = false;
    for (const Landmark& m : map.means) hit = hit || (m - t).norm() <= radius;
    if (hit) ++n;
  }
  return n;
}

}  // namespace phdslam::reference::testing
