// Test-only: small deterministic scenarios for the smoother tests. A vehicle drives one circle
// (radius speed / omega around the origin) inside a ring of landmarks, with the synthetic
// scenario's noise levels, detection probability and clutter model (docs/algorithms/models.md
// section 4.1).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/angles.h"
#include "src/core/random.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference::testing {

struct CircleScenarioOptions {
  int steps = 100;
  int landmarks = 20;
  double landmark_radius = 25.0;  ///< m, ring of landmarks centred on the circle's centre
  double speed = 1.0;             ///< m/s
  datasets::MotionKind motion = datasets::MotionKind::kVelocity;
  int sub_intervals = 1;               ///< per 1 s step (zero-order hold, same control)
  bool first_step_propagates = false;  ///< step 0 moves from the initial pose
  bool noise = true;                   ///< odometry and measurement noise
  double detection_probability = 0.95;
  double clutter_rate = 0.0;  ///< Poisson mean per scan, uniform in (r, phi) over the FOV
  std::uint64_t seed = 1;
};

inline datasets::Scenario MakeCircleScenario(const CircleScenarioOptions& o) {
  datasets::Scenario s;
  s.name = "circle";
  s.seed = o.seed;
  s.motion = o.motion;
  s.control_noise_cov = Vec2(0.64, 7.6154e-5).asDiagonal();
  s.sensor.fov_range = 50.0;
  s.sensor.fov_half_angle = DegToRad(90.0);
  s.sensor.noise_cov = Vec2(0.64, 2.7416e-5).asDiagonal();
  s.sensor.pd_max = o.detection_probability;
  s.sensor.clutter_rate = o.clutter_rate;
  const std::unique_ptr<models::MotionModel> model = s.MakeMotionModel();

  const double omega = 2.0 * std::numbers::pi / o.steps;  // one turn (rad/s)
  const double radius = o.speed / omega;
  s.initial_pose = Pose(radius, 0.0, std::numbers::pi / 2.0);
  Control u_true(o.speed, omega);
  if (o.motion == datasets::MotionKind::kCar) {
    // Steering angle giving the same turn rate: omega = v_c tan(alpha) / L with
    // v_c = v_e / (1 - H/L tan(alpha)), solved for tan(alpha).
    const double l = s.car.wheelbase_l;
    const double h = s.car.encoder_offset_h;
    const double ta = omega * l / (o.speed + omega * h);
    u_true = Control(o.speed, std::atan(ta));
  }
  for (int i = 0; i < o.landmarks; ++i) {
    const double a = 2.0 * std::numbers::pi * i / o.landmarks;
    s.truth.landmarks.emplace_back(o.landmark_radius * std::cos(a),
                                   o.landmark_radius * std::sin(a));
  }

  RandomStream rng(DeriveSeed(HashName("reference-ceres-circle-scenario"), o.seed));
  const double sv = std::sqrt(s.control_noise_cov(0, 0));
  const double sw = std::sqrt(s.control_noise_cov(1, 1));
  const double sr = std::sqrt(s.sensor.noise_cov(0, 0));
  const double sb = std::sqrt(s.sensor.noise_cov(1, 1));
  Pose x = s.initial_pose;
  for (int k = 0; k < o.steps; ++k) {
    datasets::ScenarioStep step;
    if (k == 0 && !o.first_step_propagates) {
      step.data.times = {0.0};
    } else {
      const double t0 = k == 0 ? -1.0 : k - 1.0;
      const double dt = 1.0 / o.sub_intervals;
      step.data.times.push_back(t0);
      for (int i = 0; i < o.sub_intervals; ++i) {
        Control u = u_true;
        if (o.noise) u += Control(sv * rng.Normal(), sw * rng.Normal());
        step.data.controls.push_back(u);
        step.data.times.push_back(t0 + (i + 1) * dt);
        x = model->Predict(x, u_true, dt);
      }
    }
    s.truth.poses.push_back(x);
    for (std::size_t i = 0; i < s.truth.landmarks.size(); ++i) {
      const Landmark& m = s.truth.landmarks[i];
      if (s.sensor.DetectionProbability(x, m) <= 0.0) continue;
      if (rng.Uniform() >= o.detection_probability) continue;
      Measurement z = models::PredictMeasurement(x, m);
      if (o.noise) z += Measurement(sr * rng.Normal(), sb * rng.Normal());
      z(1) = WrapAngle(z(1));
      step.data.measurements.push_back(z);
      step.origin.push_back(static_cast<int>(i));
    }
    const int clutter = rng.Poisson(o.clutter_rate);
    for (int c = 0; c < clutter; ++c) {
      const double r = rng.Uniform(0.0, s.sensor.fov_range);
      const double b = rng.Uniform(-s.sensor.fov_half_angle, s.sensor.fov_half_angle);
      step.data.measurements.emplace_back(r, b);
      step.origin.push_back(datasets::kClutter);
    }
    s.steps.push_back(std::move(step));
  }
  return s;
}

/// Root-mean-square position error of `poses` against the truth.
inline double PositionRmse(const datasets::Scenario& s, const std::vector<Pose>& poses) {
  double sum = 0.0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    sum += (poses[k].head<2>() - s.truth.poses[k].head<2>()).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(poses.size()));
}

}  // namespace phdslam::reference::testing
