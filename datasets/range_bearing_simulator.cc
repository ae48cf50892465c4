#include "datasets/range_bearing_simulator.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "datasets/simulation_limits.h"
#include "src/core/angles.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::datasets {
namespace {

[[noreturn]] void FailRangeBearingOption(std::string_view owner, std::string_view field,
                                         const std::string& what) {
  throw std::invalid_argument(std::string(owner) + "." + std::string(field) + " " + what);
}

void CheckCovariance(std::string_view owner, std::string_view field, const Mat2& cov) {
  if (!cov.allFinite()) FailRangeBearingOption(owner, field, "must be finite");
  if (cov(0, 1) != cov(1, 0)) FailRangeBearingOption(owner, field, "must be symmetric");
  const double det = cov(0, 0) * cov(1, 1) - cov(0, 1) * cov(1, 0);
  const double scale = cov(0, 0) * cov(1, 1);
  if (cov(0, 0) < 0.0 || cov(1, 1) < 0.0 || det < -1e-12 * scale) {
    FailRangeBearingOption(owner, field, "must be positive semi-definite");
  }
}

}  // namespace

void SimulationSettings::Validate(std::string_view owner) const {
  const auto str = [](double v) { return CompactNumber(v); };
  if (!(detection_probability > 0.0 && detection_probability <= 1.0)) {
    FailRangeBearingOption(owner, "detection_probability",
                           "must be in (0, 1], got " + str(detection_probability));
  }
  if (!(clutter_rate >= 0.0 && clutter_rate <= kMaxClutterRate)) {
    FailRangeBearingOption(
        owner, "clutter_rate",
        "must be in [0, " + str(kMaxClutterRate) + "] per scan, got " + str(clutter_rate));
  }
  if (!(fov_range > 0.0) || !std::isfinite(fov_range)) {
    FailRangeBearingOption(owner, "fov_range", "must be finite and > 0 (m), got " + str(fov_range));
  }
  if (!(fov_half_angle > 0.0 && fov_half_angle <= std::numbers::pi)) {
    FailRangeBearingOption(owner, "fov_half_angle",
                           "must be in (0, pi] (rad), got " + str(fov_half_angle));
  }
  if (!(range_buffer >= 0.0) || !std::isfinite(range_buffer)) {
    FailRangeBearingOption(owner, "range_buffer",
                           "must be finite and >= 0 (m), got " + str(range_buffer));
  }
  if (!(angle_buffer >= 0.0) || !std::isfinite(angle_buffer)) {
    FailRangeBearingOption(owner, "angle_buffer",
                           "must be finite and >= 0 (rad), got " + str(angle_buffer));
  }
  CheckCovariance(owner, "measurement_noise_cov", measurement_noise_cov);
  CheckCovariance(owner, "control_noise_cov", control_noise_cov);
}

models::SensorModel SimulationSettings::Sensor() const {
  models::SensorModel s;
  s.fov_range = fov_range;
  s.fov_half_angle = fov_half_angle;
  s.range_buffer = range_buffer;
  s.angle_buffer = angle_buffer;
  s.profile = models::DetectionProfile::kConstant;
  s.pd_max = detection_probability;
  s.pd_nominal = detection_probability;
  s.noise_cov = measurement_noise_cov;
  s.clutter_rate = clutter_rate;
  return s;
}

Mat2 NoiseFactor(const Mat2& cov) {
  Mat2 l = Mat2::Zero();
  l(0, 0) = std::sqrt(std::max(cov(0, 0), 0.0));
  if (l(0, 0) > 0.0) l(1, 0) = cov(1, 0) / l(0, 0);
  l(1, 1) = std::sqrt(std::max(cov(1, 1) - l(1, 0) * l(1, 0), 0.0));
  return l;
}

std::vector<ScenarioStep> SimulateRangeBearingSteps(const std::vector<Pose>& truth,
                                                    const std::vector<Control>& true_controls,
                                                    const std::vector<Landmark>& landmarks,
                                                    const SimulationSettings& settings, double dt,
                                                    RandomStream& rng) {
  if (true_controls.size() != truth.size()) {
    throw std::invalid_argument(
        "SimulateRangeBearingSteps: " + std::to_string(true_controls.size()) + " controls for " +
        std::to_string(truth.size()) + " poses; expected one per pose");
  }
  settings.Validate("SimulationSettings");
  const Mat2 meas_factor = NoiseFactor(settings.measurement_noise_cov);
  const Mat2 odo_factor = NoiseFactor(settings.control_noise_cov);
  const double range2 = settings.fov_range * settings.fov_range;
  const double half = settings.fov_half_angle;
  const double pd = settings.detection_probability;

  std::vector<ScenarioStep> steps(truth.size());
  Control previous_odometry = Control::Zero();
  std::vector<Measurement> scan;
  std::vector<int> labels;
  std::size_t held = 0;  // measurements drawn so far, before pD thinning
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const Pose& x = truth[k];
    scan.clear();
    labels.clear();
    for (std::size_t i = 0; i < landmarks.size(); ++i) {
      const double dx = landmarks[i](0) - x(0);
      const double dy = landmarks[i](1) - x(1);
      if (dx * dx + dy * dy > range2) continue;
      if (std::abs(WrapAngle(std::atan2(dy, dx) - x(2))) > half) continue;
      scan.push_back(models::PredictMeasurement(x, landmarks[i]));
      labels.push_back(static_cast<int>(i));
    }
    const int clutter = rng.Poisson(settings.clutter_rate);
    for (int c = 0; c < clutter; ++c) {
      const double r = rng.Uniform(0.0, settings.fov_range);
      const double phi = rng.Uniform(-half, half);
      scan.emplace_back(r, phi);
      labels.push_back(kClutter);
    }
    for (Measurement& z : scan) {
      const double n0 = rng.Normal();
      const double n1 = rng.Normal();
      z += meas_factor * Vec2(n0, n1);
    }
    held += scan.size();
    if (static_cast<double>(held) > kMaxSimulatedMeasurements) {
      throw std::invalid_argument(
          "simulated scenario: more than " + CompactNumber(kMaxSimulatedMeasurements) +
          " measurements (landmarks in view and clutter) by step " + std::to_string(k) +
          ", the simulator's cap; reduce steps, landmarks, fov_range or clutter_rate");
    }
    ScenarioStep& step = steps[k];
    for (std::size_t j = 0; j < scan.size(); ++j) {
      if (!(rng.Uniform() < pd)) continue;
      step.data.measurements.emplace_back(scan[j](0), WrapAngle(scan[j](1)));
      step.origin.push_back(labels[j]);
    }
    const double n0 = rng.Normal();
    const double n1 = rng.Normal();
    const Control odometry = true_controls[k] + odo_factor * Vec2(n0, n1);

    const double t = static_cast<double>(k) * dt;
    if (k == 0) {
      step.data.times = {t};
    } else {
      step.data.times = {static_cast<double>(k - 1) * dt, t};
      step.data.controls = {previous_odometry};
    }
    previous_odometry = odometry;
  }
  return steps;
}

}  // namespace phdslam::datasets
