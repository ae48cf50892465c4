#include "datasets/scenario_check.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace phdslam::datasets {
namespace {

/// Builds and throws the error message "<source>: <where>: <what>".
class Reporter {
 public:
  explicit Reporter(std::string_view source) : source_(source) {}

  [[noreturn]] void Fail(const std::string& where, const std::string& what) const {
    throw std::invalid_argument(source_ + ": " + where + ": " + what);
  }

  void CheckFinite(double value, const std::string& where, const std::string& field) const {
    if (!std::isfinite(value)) Fail(where, field + " is " + Describe(value));
  }

  template <typename Derived>
  void CheckFinite(const Eigen::MatrixBase<Derived>& m, const std::string& where,
                   const std::string& field) const {
    for (Eigen::Index c = 0; c < m.cols(); ++c) {
      for (Eigen::Index r = 0; r < m.rows(); ++r) {
        if (!std::isfinite(m(r, c))) {
          std::string entry = field;
          if (m.cols() == 1) {
            entry.append("[").append(std::to_string(r)).append("]");
          } else {
            entry.append("(").append(std::to_string(r)).append(", ");
            entry.append(std::to_string(c)).append(")");
          }
          Fail(where, entry + " is " + Describe(m(r, c)));
        }
      }
    }
  }

  void CheckRange(bool ok, double value, const std::string& where, const std::string& field,
                  const std::string& expected) const {
    if (!ok) Fail(where, field + " must be " + expected + ", got " + Describe(value));
  }

  static std::string Describe(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
  }

 private:
  std::string source_;
};

std::string StepName(std::size_t k) { return "step " + std::to_string(k); }

void CheckParameters(const Scenario& s, const Reporter& rep) {
  const std::string where = "parameters";
  rep.CheckFinite(s.initial_pose, where, "initial_pose");
  rep.CheckFinite(s.control_noise_cov, where, "control_noise_cov");
  const models::SensorModel& sn = s.sensor;
  rep.CheckRange(sn.fov_range > 0.0 && std::isfinite(sn.fov_range), sn.fov_range, where,
                 "sensor.fov_range", "finite and > 0");
  rep.CheckRange(sn.fov_half_angle > 0.0 && sn.fov_half_angle <= std::numbers::pi,
                 sn.fov_half_angle, where, "sensor.fov_half_angle", "in (0, pi]");
  rep.CheckRange(sn.range_buffer >= 0.0 && std::isfinite(sn.range_buffer), sn.range_buffer, where,
                 "sensor.range_buffer", "finite and >= 0");
  rep.CheckRange(sn.angle_buffer >= 0.0 && std::isfinite(sn.angle_buffer), sn.angle_buffer, where,
                 "sensor.angle_buffer", "finite and >= 0");
  rep.CheckRange(sn.pd_max >= 0.0 && sn.pd_max <= 1.0, sn.pd_max, where, "sensor.pd_max",
                 "in [0, 1]");
  rep.CheckRange(sn.pd_nominal > 0.0 && sn.pd_nominal <= 1.0, sn.pd_nominal, where,
                 "sensor.pd_nominal", "in (0, 1]");
  rep.CheckFinite(sn.noise_cov, where, "sensor.noise_cov");
  rep.CheckRange(sn.clutter_rate >= 0.0 && std::isfinite(sn.clutter_rate), sn.clutter_rate, where,
                 "sensor.clutter_rate", "finite and >= 0");
  if (s.motion == MotionKind::kCar) {
    rep.CheckRange(s.car.wheelbase_l > 0.0 && std::isfinite(s.car.wheelbase_l), s.car.wheelbase_l,
                   where, "car.wheelbase_l", "finite and > 0");
    rep.CheckFinite(s.car.encoder_offset_h, where, "car.encoder_offset_h");
    rep.CheckFinite(s.car.laser_a, where, "car.laser_a");
    rep.CheckFinite(s.car.laser_b, where, "car.laser_b");
  }
}

void CheckStep(const ScenarioStep& step, std::size_t k, double* last_time,
               std::size_t landmark_count, const Reporter& rep) {
  const std::string where = StepName(k);
  const StepData& d = step.data;
  if (d.times.empty()) rep.Fail(where, "times is empty (expected at least one time stamp)");
  for (std::size_t i = 0; i < d.times.size(); ++i) {
    const std::string field = "times[" + std::to_string(i) + "]";
    rep.CheckFinite(d.times[i], where, field);
    if (d.times[i] < *last_time) {
      rep.Fail(where, field + " = " + Reporter::Describe(d.times[i]) +
                          " is earlier than the time before it, " + Reporter::Describe(*last_time) +
                          " (times must be non-decreasing)");
    }
    *last_time = d.times[i];
  }
  if (d.controls.size() != d.times.size() - 1) {
    rep.Fail(where, "controls.size() is " + std::to_string(d.controls.size()) +
                        ", expected times.size() - 1 = " + std::to_string(d.times.size() - 1));
  }
  for (std::size_t i = 0; i < d.controls.size(); ++i) {
    const std::string field = where + ": control " + std::to_string(i);
    rep.CheckFinite(d.controls[i](0), field, "component 0");
    rep.CheckFinite(d.controls[i](1), field, "component 1");
  }
  for (std::size_t j = 0; j < d.measurements.size(); ++j) {
    const std::string field = where + ": measurement " + std::to_string(j);
    rep.CheckFinite(d.measurements[j](0), field, "range");
    rep.CheckFinite(d.measurements[j](1), field, "bearing");
  }
  if (!step.origin.empty() && step.origin.size() != d.measurements.size()) {
    rep.Fail(where, "origin.size() is " + std::to_string(step.origin.size()) +
                        ", expected 0 (unknown) or measurements.size() = " +
                        std::to_string(d.measurements.size()));
  }
  for (std::size_t j = 0; j < step.origin.size(); ++j) {
    const int o = step.origin[j];
    const bool valid =
        o == kClutter || o == kUnknownOrigin ||
        (o >= 0 && (landmark_count == 0 || static_cast<std::size_t>(o) < landmark_count));
    if (!valid) {
      rep.Fail(where,
               "origin[" + std::to_string(j) + "] is " + std::to_string(o) +
                   ", expected kClutter (-1), kUnknownOrigin (-2) or a landmark index below " +
                   std::to_string(landmark_count));
    }
  }
}

}  // namespace

void CheckScenario(const Scenario& scenario, std::string_view source) {
  const Reporter rep(source);
  CheckParameters(scenario, rep);
  const GroundTruth& truth = scenario.truth;
  double last_time = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    CheckStep(scenario.steps[k], k, &last_time, truth.landmarks.size(), rep);
  }
  if (!truth.poses.empty() && truth.poses.size() != scenario.steps.size()) {
    rep.Fail("truth", "poses.size() is " + std::to_string(truth.poses.size()) +
                          ", expected 0 or one per step (" + std::to_string(scenario.steps.size()) +
                          ")");
  }
  for (std::size_t k = 0; k < truth.poses.size(); ++k) {
    rep.CheckFinite(truth.poses[k], "truth: " + StepName(k), "pose");
  }
  for (std::size_t i = 0; i < truth.landmarks.size(); ++i) {
    rep.CheckFinite(truth.landmarks[i], "truth: landmark " + std::to_string(i), "position");
  }
  for (std::size_t i = 0; i < truth.gps.size(); ++i) {
    rep.CheckFinite(truth.gps[i].t, "truth: gps fix " + std::to_string(i), "t");
    rep.CheckFinite(truth.gps[i].position, "truth: gps fix " + std::to_string(i), "position");
  }
}

}  // namespace phdslam::datasets
