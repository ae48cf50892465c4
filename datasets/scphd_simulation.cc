#include "datasets/scphd_simulation.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/range_bearing_simulator.h"
#include "datasets/simulation_limits.h"
#include "src/core/random.h"
#include "src/models/car_motion_model.h"

namespace phdslam::datasets {
namespace {

constexpr const char* kScPhdSimName = "scphd-sim";
constexpr const char* kMapStreamName = "scphd-sim/map";

[[noreturn]] void FailScPhdSimOption(const std::string& field, const std::string& what) {
  throw std::invalid_argument("ScPhdSimOptions." + field + " " + what);
}

void RequirePositiveScPhdSimOption(const std::string& field, double v) {
  if (!(v > 0.0) || !std::isfinite(v))
    FailScPhdSimOption(field, "must be finite and > 0, got " + CompactNumber(v));
}

// The heading change per step that makes each Euler step of length v dt a chord of the circle.
double TurnPerStep(const ScPhdSimOptions& o) {
  return 2.0 * std::asin(o.speed * o.dt / (2.0 * o.circle_radius));
}

}  // namespace

ScPhdSimOptions::ScPhdSimOptions() {
  measurement_noise_cov = Vec2(1.0, DegToRad(2.0) * DegToRad(2.0)).asDiagonal();
  control_noise_cov = Vec2(2.0 * 2.0, DegToRad(5.0) * DegToRad(5.0)).asDiagonal();
}

void ScPhdSimOptions::Validate() const {
  if (steps < 1) FailScPhdSimOption("steps", "must be >= 1, got " + std::to_string(steps));
  RequirePositiveScPhdSimOption("dt", dt);
  RequirePositiveScPhdSimOption("speed", speed);
  RequirePositiveScPhdSimOption("circle_radius", circle_radius);
  RequirePositiveScPhdSimOption("wheelbase", wheelbase);
  if (speed * dt >= 2.0 * circle_radius)
    FailScPhdSimOption("speed", "* dt must be below the circle's diameter (2 x circle_radius)");
  if (landmarks < 0)
    FailScPhdSimOption("landmarks", "must be >= 0, got " + std::to_string(landmarks));
  if (!(map_inner_radius >= 0.0) || !(map_outer_radius > map_inner_radius) ||
      !std::isfinite(map_outer_radius)) {
    FailScPhdSimOption("map_outer_radius", "must be finite and > map_inner_radius >= 0");
  }
  SimulationSettings::Of(*this).Validate("ScPhdSimOptions");
  CheckSimulationSize("ScPhdSimOptions", steps, landmarks, clutter_rate);
}

std::vector<Landmark> ScPhdSimMap(const ScPhdSimOptions& o) {
  RandomStream rng(HashName(kMapStreamName));
  const double r0 = o.map_inner_radius * o.map_inner_radius;
  const double r1 = o.map_outer_radius * o.map_outer_radius;
  std::vector<Landmark> map;
  map.reserve(static_cast<std::size_t>(o.landmarks));
  for (int i = 0; i < o.landmarks; ++i) {
    // Uniform over the annulus: r^2 uniform on [r0^2, r1^2], angle uniform.
    const double r = std::sqrt(r0 + (r1 - r0) * rng.Uniform());
    const double phi = 2.0 * std::numbers::pi * rng.Uniform();
    map.emplace_back(r * std::cos(phi), r * std::sin(phi));
  }
  return map;
}

Scenario MakeScPhdSimScenario(const ScPhdSimOptions& options, std::uint64_t seed) {
  options.Validate();
  Scenario s;
  s.name = kScPhdSimName;
  s.seed = seed;
  const double turn = TurnPerStep(options);
  // Heading the first chord: the poses are the vertices of a regular polygon on the circle.
  s.initial_pose = Pose(options.circle_radius, 0.0, std::numbers::pi / 2.0 + turn / 2.0);
  s.motion = MotionKind::kCar;
  s.car = models::CarGeometry::Bicycle(options.wheelbase);
  s.control_noise_cov = options.control_noise_cov;
  const SimulationSettings settings = SimulationSettings::Of(options);
  s.sensor = settings.Sensor();
  s.truth.landmarks = ScPhdSimMap(options);

  const models::CarMotionModel motion(s.car);
  const double step = options.speed * options.dt;
  const Control u(options.speed, std::atan(options.wheelbase * turn / step));
  std::vector<Pose> poses;
  std::vector<Control> controls;
  Pose x = s.initial_pose;
  for (int k = 0; k < options.steps; ++k) {
    poses.push_back(x);
    controls.push_back(u);
    x = motion.Predict(x, u, options.dt);
  }
  RandomStream rng(DeriveSeed(HashName(kScPhdSimName), seed));
  s.steps =
      SimulateRangeBearingSteps(poses, controls, s.truth.landmarks, settings, options.dt, rng);
  s.truth.poses = std::move(poses);
  return s;
}

}  // namespace phdslam::datasets
