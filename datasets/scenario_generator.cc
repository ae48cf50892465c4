#include "datasets/scenario_generator.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/range_bearing_simulator.h"
#include "datasets/simulation_limits.h"
#include "src/core/random.h"
#include "src/models/velocity_motion_model.h"

namespace phdslam::datasets {
namespace {

constexpr const char* kGeneratedName = "generated";
constexpr const char* kLandmarkStreamName = "generated/landmarks";
constexpr double kCellsPerHalfWidth = 32.0;
constexpr double kMaxRasterCells = 4.0e7;

/// Turn rate of the smooth profile at time t (see the header).
double TurnRate(double amplitude, double t) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  return amplitude *
         (0.5 * std::sin(kTwoPi * t / 400.0 + 0.3) + 0.3 * std::sin(kTwoPi * t / 170.0 + 1.9) +
          0.2 * std::sin(kTwoPi * t / 1100.0 + 4.1));
}

struct TruePath {
  std::vector<Pose> poses;
  std::vector<Control> controls;  ///< controls[k] drives poses[k] -> poses[k + 1]
};

TruePath MakeTruePath(const GeneratorOptions& o) {
  TruePath path;
  const auto n = static_cast<std::size_t>(o.steps);
  path.poses.reserve(n);
  path.controls.reserve(n);
  const models::VelocityMotionModel motion;
  Pose x = o.initial_pose;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * o.dt;
    path.poses.push_back(x);
    path.controls.emplace_back(o.speed, TurnRate(o.turn_amplitude, t));
    x = motion.Predict(x, path.controls.back(), o.dt);
  }
  return path;
}

double DistanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

/// The corridor (points within half_width of the path polyline) on a square grid.
struct CorridorRaster {
  double x0 = 0.0;
  double y0 = 0.0;
  double cell = 1.0;
  long nx = 0;
  long ny = 0;
  std::vector<long> inside_cells;  ///< indices iy * nx + ix of the cells inside, ascending

  [[nodiscard]] double Area() const {
    return static_cast<double>(inside_cells.size()) * cell * cell;
  }
};

CorridorRaster RasteriseCorridor(const std::vector<Pose>& poses, double half_width) {
  double min_x = poses.front()(0);
  double max_x = min_x;
  double min_y = poses.front()(1);
  double max_y = min_y;
  for (const Pose& p : poses) {
    min_x = std::min(min_x, p(0));
    max_x = std::max(max_x, p(0));
    min_y = std::min(min_y, p(1));
    max_y = std::max(max_y, p(1));
  }
  CorridorRaster r;
  r.x0 = min_x - half_width;
  r.y0 = min_y - half_width;
  const double width = max_x - min_x + 2.0 * half_width;
  const double height = max_y - min_y + 2.0 * half_width;
  r.cell = std::max(half_width / kCellsPerHalfWidth, std::sqrt(width * height / kMaxRasterCells));
  r.nx = static_cast<long>(std::ceil(width / r.cell));
  r.ny = static_cast<long>(std::ceil(height / r.cell));
  std::vector<unsigned char> inside(static_cast<std::size_t>(r.nx * r.ny), 0);

  const auto mark_segment = [&](const Vec2& a, const Vec2& b) {
    const auto cell_range = [&](double lo, double hi, double origin, long n) {
      const long first = std::max(0L, static_cast<long>(std::floor((lo - origin) / r.cell)));
      const long last = std::min(n - 1, static_cast<long>(std::floor((hi - origin) / r.cell)));
      return std::pair<long, long>(first, last);
    };
    const auto [ix0, ix1] = cell_range(std::min(a(0), b(0)) - half_width,
                                       std::max(a(0), b(0)) + half_width, r.x0, r.nx);
    const auto [iy0, iy1] = cell_range(std::min(a(1), b(1)) - half_width,
                                       std::max(a(1), b(1)) + half_width, r.y0, r.ny);
    for (long iy = iy0; iy <= iy1; ++iy) {
      for (long ix = ix0; ix <= ix1; ++ix) {
        unsigned char& flag = inside[static_cast<std::size_t>(iy * r.nx + ix)];
        if (flag != 0) continue;
        const Vec2 centre(r.x0 + (static_cast<double>(ix) + 0.5) * r.cell,
                          r.y0 + (static_cast<double>(iy) + 0.5) * r.cell);
        if (DistanceToSegment(centre, a, b) <= half_width) flag = 1;
      }
    }
  };
  if (poses.size() == 1) mark_segment(poses[0].head<2>(), poses[0].head<2>());
  for (std::size_t k = 1; k < poses.size(); ++k) {
    mark_segment(poses[k - 1].head<2>(), poses[k].head<2>());
  }
  for (std::size_t i = 0; i < inside.size(); ++i) {
    if (inside[i] != 0) r.inside_cells.push_back(static_cast<long>(i));
  }
  return r;
}

[[noreturn]] void FailGeneratorOption(const std::string& field, const std::string& what) {
  throw std::invalid_argument("GeneratorOptions." + field + " " + what);
}

}  // namespace

GeneratorOptions::GeneratorOptions() {
  measurement_noise_cov = Vec2(0.8 * 0.8, DegToRad(0.3) * DegToRad(0.3)).asDiagonal();
  control_noise_cov = Vec2(0.8 * 0.8, DegToRad(0.5) * DegToRad(0.5)).asDiagonal();
}

void GeneratorOptions::Validate() const {
  const auto str = [](double v) { return CompactNumber(v); };
  if (steps < 1) FailGeneratorOption("steps", "must be >= 1, got " + std::to_string(steps));
  if (!(dt > 0.0) || !std::isfinite(dt))
    FailGeneratorOption("dt", "must be finite and > 0 (s), got " + str(dt));
  if (!(speed >= 0.0) || !std::isfinite(speed)) {
    FailGeneratorOption("speed", "must be finite and >= 0 (m/s), got " + str(speed));
  }
  if (!(turn_amplitude >= 0.0) || !std::isfinite(turn_amplitude)) {
    FailGeneratorOption("turn_amplitude",
                        "must be finite and >= 0 (rad/s), got " + str(turn_amplitude));
  }
  if (landmarks < 0)
    FailGeneratorOption("landmarks", "must be >= 0, got " + std::to_string(landmarks));
  if (!(corridor_half_width >= kMinCorridorHalfWidth) || !std::isfinite(corridor_half_width)) {
    FailGeneratorOption("corridor_half_width",
                        "must be finite and >= " + str(kMinCorridorHalfWidth) + " (m), got " +
                            str(corridor_half_width));
  }
  if (!initial_pose.allFinite()) FailGeneratorOption("initial_pose", "must be finite");
  SimulationSettings::Of(*this).Validate("GeneratorOptions");
  CheckSimulationSize("GeneratorOptions", steps, landmarks, clutter_rate);
}

Scenario GenerateScenario(const GeneratorOptions& options, std::uint64_t seed) {
  return GenerateScenarioPrefix(options, seed, options.steps);
}

Scenario GenerateScenarioPrefix(const GeneratorOptions& options, std::uint64_t seed,
                                int simulated_steps) {
  options.Validate();
  if (simulated_steps < 1 || simulated_steps > options.steps) {
    throw std::invalid_argument("GenerateScenarioPrefix: simulated_steps must be in [1, " +
                                std::to_string(options.steps) + "], got " +
                                std::to_string(simulated_steps));
  }
  TruePath path = MakeTruePath(options);

  Scenario s;
  s.name = kGeneratedName;
  s.seed = seed;
  s.initial_pose = options.initial_pose;
  s.motion = MotionKind::kVelocity;
  s.control_noise_cov = options.control_noise_cov;
  const SimulationSettings settings = SimulationSettings::Of(options);
  s.sensor = settings.Sensor();

  const CorridorRaster corridor = RasteriseCorridor(path.poses, options.corridor_half_width);
  RandomStream landmark_rng(DeriveSeed(HashName(kLandmarkStreamName), seed));
  const auto cells = static_cast<double>(corridor.inside_cells.size());
  s.truth.landmarks.reserve(static_cast<std::size_t>(options.landmarks));
  for (int i = 0; i < options.landmarks; ++i) {
    const auto pick = std::min(static_cast<std::size_t>(landmark_rng.Uniform() * cells),
                               corridor.inside_cells.size() - 1);
    const long index = corridor.inside_cells[pick];
    const double ix = static_cast<double>(index % corridor.nx) + landmark_rng.Uniform();
    const long row = index / corridor.nx;
    const double iy = static_cast<double>(row) + landmark_rng.Uniform();
    s.truth.landmarks.emplace_back(corridor.x0 + ix * corridor.cell,
                                   corridor.y0 + iy * corridor.cell);
  }

  // The scans depend only on the steps before them, so simulating a prefix gives the same ones.
  const auto prefix = static_cast<std::size_t>(simulated_steps);
  path.poses.resize(prefix);
  path.controls.resize(prefix);
  RandomStream rng(DeriveSeed(HashName(kGeneratedName), seed));
  s.steps = SimulateRangeBearingSteps(path.poses, path.controls, s.truth.landmarks, settings,
                                      options.dt, rng);
  s.truth.poses = std::move(path.poses);
  return s;
}

GeneratorOptions OptionsForLandmarksInView(int landmarks_in_fov, int steps) {
  if (landmarks_in_fov < 0) {
    throw std::invalid_argument("OptionsForLandmarksInView: landmarks_in_fov must be >= 0, got " +
                                std::to_string(landmarks_in_fov));
  }
  if (steps < 1) {
    throw std::invalid_argument("OptionsForLandmarksInView: steps must be >= 1, got " +
                                std::to_string(steps));
  }
  GeneratorOptions o;
  o.steps = steps;
  o.corridor_half_width = o.fov_range;
  const double sector_area = o.fov_half_angle * o.fov_range * o.fov_range;
  const double corridor_area =
      RasteriseCorridor(MakeTruePath(o).poses, o.corridor_half_width).Area();
  o.landmarks = static_cast<int>(std::lround(landmarks_in_fov * corridor_area / sector_area));
  return o;
}

}  // namespace phdslam::datasets
