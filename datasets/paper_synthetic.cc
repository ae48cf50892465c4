#include "datasets/paper_synthetic.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "datasets/mat_file.h"
#include "datasets/range_bearing_simulator.h"
#include "src/core/random.h"
#include "src/models/velocity_motion_model.h"

namespace phdslam::datasets {
namespace {

constexpr const char* kPaperSyntheticName = "paper-synthetic";

std::string Shape(const Eigen::MatrixXd& m) {
  return std::to_string(m.rows()) + " x " + std::to_string(m.cols());
}

// Reads a variable with exactly `rows` rows (any number >= 1 when rows == 0) and at least
// `min_cols` columns, all finite.
Eigen::MatrixXd ReadChecked(const MatFile& file, const std::string& name, Eigen::Index rows,
                            Eigen::Index min_cols, const std::string& expected) {
  Eigen::MatrixXd m = file.ReadMatrix(name);
  const bool rows_ok = rows > 0 ? m.rows() == rows : m.rows() >= 1;
  if (!rows_ok || m.cols() < min_cols) {
    throw std::runtime_error("MAT-file '" + file.path().string() + "', variable '" + name +
                             "': expected " + expected + ", found " + Shape(m));
  }
  for (Eigen::Index c = 0; c < m.cols(); ++c) {
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
      if (!std::isfinite(m(r, c))) {
        throw std::runtime_error("MAT-file '" + file.path().string() + "', variable '" + name +
                                 "': entry (" + std::to_string(r + 1) + ", " +
                                 std::to_string(c + 1) + ") is not finite");
      }
    }
  }
  return m;
}

}  // namespace

std::vector<std::filesystem::path> PaperSyntheticDataFiles() {
  return {std::filesystem::path("phdslam3-synthetic") / "Environment_SLAM.mat"};
}

PaperSyntheticEnvironment LoadPaperSyntheticEnvironment(const std::filesystem::path& data_dir) {
  const MatFile file(data_dir / PaperSyntheticDataFiles().front());
  // Landmark_Groundtruth: one row per landmark, columns 2-3 hold x, y.
  const Eigen::MatrixXd lm =
      ReadChecked(file, "Landmark_Groundtruth", 0, 3, "N x 5 (N >= 1, at least 3 columns)");
  const Eigen::MatrixXd u = ReadChecked(file, "Robot_Control", 2, 1, "2 x K (K >= 1)");
  const Eigen::MatrixXd gt = ReadChecked(file, "Robot_Groundtruth", 3, 1, "3 x K (K >= 1)");

  PaperSyntheticEnvironment env;
  env.landmarks.reserve(static_cast<std::size_t>(lm.rows()));
  for (Eigen::Index i = 0; i < lm.rows(); ++i) env.landmarks.emplace_back(lm(i, 1), lm(i, 2));
  env.true_controls.reserve(static_cast<std::size_t>(u.cols()));
  for (Eigen::Index k = 0; k < u.cols(); ++k) env.true_controls.emplace_back(u(0, k), u(1, k));
  env.initial_pose = gt.col(0);
  return env;
}

SyntheticOptions::SyntheticOptions() {
  measurement_noise_cov = Vec2(0.8 * 0.8, DegToRad(0.3) * DegToRad(0.3)).asDiagonal();
  control_noise_cov = Vec2(0.8 * 0.8, DegToRad(0.5) * DegToRad(0.5)).asDiagonal();
}

void SyntheticOptions::Validate() const {
  if (steps < 0) {
    throw std::invalid_argument("SyntheticOptions.steps must be >= 0 (0 = all), got " +
                                std::to_string(steps));
  }
  SimulationSettings::Of(*this).Validate("SyntheticOptions");
}

Scenario MakePaperSyntheticScenario(const PaperSyntheticEnvironment& env, std::uint64_t seed,
                                    const SyntheticOptions& options) {
  options.Validate();
  const auto available = env.true_controls.size();
  if (available == 0) {
    throw std::invalid_argument("MakePaperSyntheticScenario: the environment has no controls");
  }
  const std::size_t steps =
      options.steps == 0 ? available : static_cast<std::size_t>(options.steps);
  if (steps > available) {
    throw std::invalid_argument("SyntheticOptions.steps must be at most " +
                                std::to_string(available) + " (the controls available), got " +
                                std::to_string(options.steps));
  }
  constexpr double kDt = 1.0;

  Scenario s;
  s.name = kPaperSyntheticName;
  s.seed = seed;
  s.initial_pose = env.initial_pose;
  s.motion = MotionKind::kVelocity;
  s.control_noise_cov = options.control_noise_cov;
  const SimulationSettings settings = SimulationSettings::Of(options);
  s.sensor = settings.Sensor();

  // Truth: x_1 = x_0; x_k = f(x_{k-1}, u_true_{k-1}, dt) (docs/algorithms/models.md section 5.2).
  const models::VelocityMotionModel motion;
  std::vector<Control> controls(env.true_controls.begin(),
                                env.true_controls.begin() + static_cast<std::ptrdiff_t>(steps));
  s.truth.poses.reserve(steps);
  s.truth.poses.push_back(env.initial_pose);
  for (std::size_t k = 1; k < steps; ++k) {
    s.truth.poses.push_back(motion.Predict(s.truth.poses.back(), controls[k - 1], kDt));
  }
  s.truth.landmarks = env.landmarks;

  RandomStream rng(DeriveSeed(HashName(kPaperSyntheticName), seed));
  s.steps = SimulateRangeBearingSteps(s.truth.poses, controls, env.landmarks, settings, kDt, rng);
  return s;
}

}  // namespace phdslam::datasets
