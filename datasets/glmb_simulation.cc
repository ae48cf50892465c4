#include "datasets/glmb_simulation.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/range_bearing_simulator.h"
#include "datasets/simulation_limits.h"
#include "src/core/random.h"
#include "src/models/car_motion_model.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::datasets {
namespace {

constexpr const char* kGlmbSimName = "glmb-sim";
constexpr const char* kDataStreamName = "glmb-sim/data";
constexpr const char* kClutterStreamName = "glmb-sim/clutter";

// One lap: a straight then a 90 deg left corner, four times (long, short, long, short).
constexpr int kLongSteps = 24;
constexpr int kShortSteps = 14;
constexpr int kCornerSteps = 12;
static_assert(2 * kLongSteps + 2 * kShortSteps + 4 * kCornerSteps == kGlmbSimLoopSteps);

[[noreturn]] void FailGlmbSimOption(const std::string& field, const std::string& what) {
  throw std::invalid_argument("GlmbSimOptions." + field + " " + what);
}

void RequirePositiveGlmbSimOption(const std::string& field, double v) {
  if (!(v > 0.0) || !std::isfinite(v))
    FailGlmbSimOption(field, "must be finite and > 0, got " + CompactNumber(v));
}

// The steering angle whose kCornerSteps Euler steps turn the heading by exactly 90 deg.
double CornerSteering(const GlmbSimOptions& o) {
  const double turn_per_step = (std::numbers::pi / 2.0) / kCornerSteps;
  return std::atan(o.wheelbase * turn_per_step / (o.speed * o.dt));
}

// True when step `phase` (0 <= phase < kGlmbSimLoopSteps) of the lap is in a corner.
bool InCorner(int phase) {
  const int sides[4] = {kLongSteps, kShortSteps, kLongSteps, kShortSteps};
  int start = 0;
  for (const int side : sides) {
    if (phase < start + side) return false;
    if (phase < start + side + kCornerSteps) return true;
    start += side + kCornerSteps;
  }
  return false;
}

std::uint64_t DataSeed(const GlmbSimOptions& o, std::uint64_t seed) {
  return o.data_protocol == GlmbDataProtocol::kSingleRealisation
             ? static_cast<std::uint64_t>(o.data_seed)
             : seed;
}

// The detections of the landmarks in view at x, then the clutter of the scan.
void SimulateScan(const Pose& x, const std::vector<Landmark>& landmarks, const GlmbSimOptions& o,
                  const Mat2& noise_factor, RandomStream& data, RandomStream& clutter,
                  ScenarioStep& step) {
  const double range2 = o.fov_range * o.fov_range;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const double dx = landmarks[i](0) - x(0);
    const double dy = landmarks[i](1) - x(1);
    if (dx * dx + dy * dy > range2) continue;
    if (std::abs(WrapAngle(std::atan2(dy, dx) - x(2))) > o.fov_half_angle) continue;
    const bool detected = data.Uniform() < o.detection_probability;
    const double n0 = data.Normal();
    const double n1 = data.Normal();
    if (!detected) continue;
    const Measurement z = models::PredictMeasurement(x, landmarks[i]) + noise_factor * Vec2(n0, n1);
    step.data.measurements.emplace_back(z(0), WrapAngle(z(1)));
    step.origin.push_back(static_cast<int>(i));
  }
  const int count = clutter.Poisson(o.clutter_rate);
  for (int c = 0; c < count; ++c) {
    const double r = clutter.Uniform(0.0, o.fov_range);
    const double phi = clutter.Uniform(-o.fov_half_angle, o.fov_half_angle);
    step.data.measurements.emplace_back(r, phi);
    step.origin.push_back(kClutter);
  }
}

}  // namespace

GlmbSimOptions::GlmbSimOptions() {
  const double sb = DegToRad(0.5);
  const double sa = DegToRad(2.0);
  measurement_noise_cov = Vec2(0.05 * 0.05, sb * sb).asDiagonal();
  control_noise_cov = Vec2(0.1 * 0.1, sa * sa).asDiagonal();
}

void GlmbSimOptions::Validate() const {
  if (steps < 1) FailGlmbSimOption("steps", "must be >= 1, got " + std::to_string(steps));
  RequirePositiveGlmbSimOption("dt", dt);
  RequirePositiveGlmbSimOption("speed", speed);
  RequirePositiveGlmbSimOption("wheelbase", wheelbase);
  if (landmarks < 0)
    FailGlmbSimOption("landmarks", "must be >= 0, got " + std::to_string(landmarks));
  if (!(landmark_offset >= 0.0) || !std::isfinite(landmark_offset)) {
    FailGlmbSimOption("landmark_offset",
                      "must be finite and >= 0 (m), got " + std::to_string(landmark_offset));
  }
  if (data_seed < 0)
    FailGlmbSimOption("data_seed", "must be >= 0, got " + std::to_string(data_seed));
  SimulationSettings::Of(*this).Validate("GlmbSimOptions");
  CheckSimulationSize("GlmbSimOptions", steps, landmarks, clutter_rate);
}

GlmbSimPath GlmbSimTruePath(const GlmbSimOptions& o, int steps) {
  const models::CarMotionModel motion(models::CarGeometry::Bicycle(o.wheelbase));
  const Control straight(o.speed, 0.0);
  const Control corner(o.speed, CornerSteering(o));
  GlmbSimPath path;
  path.poses.reserve(static_cast<std::size_t>(steps));
  path.controls.reserve(static_cast<std::size_t>(steps));
  Pose x = Pose::Zero();
  for (int k = 0; k < steps; ++k) {
    const Control& u = InCorner(k % kGlmbSimLoopSteps) ? corner : straight;
    path.poses.push_back(x);
    path.controls.push_back(u);
    x = motion.Predict(x, u, o.dt);
  }
  return path;
}

std::vector<Landmark> GlmbSimMap(const GlmbSimOptions& o) {
  const GlmbSimPath lap = GlmbSimTruePath(o, kGlmbSimLoopSteps);
  std::vector<Landmark> map;
  map.reserve(static_cast<std::size_t>(o.landmarks));
  for (int i = 0; i < o.landmarks; ++i) {
    const double s = (i + 0.5) * kGlmbSimLoopSteps / o.landmarks;
    const auto k =
        static_cast<std::size_t>(std::lround(s)) % static_cast<std::size_t>(kGlmbSimLoopSteps);
    const Pose& x = lap.poses[k];
    const double side = (i % 2 == 0) ? 1.0 : -1.0;  // left of the path = inside the loop
    map.emplace_back(x(0) - side * o.landmark_offset * std::sin(x(2)),
                     x(1) + side * o.landmark_offset * std::cos(x(2)));
  }
  return map;
}

Scenario MakeGlmbSimScenario(const GlmbSimOptions& options, std::uint64_t seed) {
  options.Validate();
  Scenario s;
  s.name = kGlmbSimName;
  s.seed = seed;
  s.initial_pose = Pose::Zero();
  s.motion = MotionKind::kCar;
  s.car = models::CarGeometry::Bicycle(options.wheelbase);
  s.control_noise_cov = options.control_noise_cov;
  s.sensor = SimulationSettings::Of(options).Sensor();
  s.sensor.clutter_space = models::ClutterSpace::kRangeBearingBox;
  s.truth.landmarks = GlmbSimMap(options);

  GlmbSimPath path = GlmbSimTruePath(options, options.steps);
  const std::uint64_t data_seed = DataSeed(options, seed);
  RandomStream data(DeriveSeed(HashName(kDataStreamName), data_seed));
  RandomStream clutter(DeriveSeed(HashName(kClutterStreamName), data_seed));
  const Mat2 meas_factor = NoiseFactor(options.measurement_noise_cov);
  const Mat2 odo_factor = NoiseFactor(options.control_noise_cov);
  s.steps.resize(path.poses.size());
  Control previous_odometry = Control::Zero();
  for (std::size_t k = 0; k < path.poses.size(); ++k) {
    ScenarioStep& step = s.steps[k];
    SimulateScan(path.poses[k], s.truth.landmarks, options, meas_factor, data, clutter, step);
    const double n0 = data.Normal();
    const double n1 = data.Normal();
    const double t = static_cast<double>(k) * options.dt;
    if (k == 0) {
      step.data.times = {t};
    } else {
      step.data.times = {static_cast<double>(k - 1) * options.dt, t};
      step.data.controls = {previous_odometry};
    }
    previous_odometry = path.controls[k] + odo_factor * Vec2(n0, n1);
  }
  s.truth.poses = std::move(path.poses);
  return s;
}

}  // namespace phdslam::datasets
