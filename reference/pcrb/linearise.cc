#include "reference/pcrb/linearise.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>

#include "reference/pcrb/information_reduction.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference::pcrb {
namespace {

std::string Prefix(const std::string& who, const datasets::Scenario& s) {
  return "estimator '" + who + "' on scenario '" + s.name + "': ";
}

void RequirePositiveDefinite(const Mat2& m, const std::string& prefix, const std::string& what) {
  if (!m.allFinite() || (m - m.transpose()).cwiseAbs().maxCoeff() > 1e-12 * m.norm() ||
      Eigen::LLT<Mat2>(m).info() != Eigen::Success) {
    throw std::invalid_argument(prefix + what + " is not finite, symmetric and positive definite");
  }
}

void CheckScenario(const datasets::Scenario& s, const PcrbParams& p, const std::string& prefix) {
  if (s.truth.poses.size() != s.steps.size() || s.truth.landmarks.empty()) {
    throw std::invalid_argument(prefix +
                                "the bound needs the true trajectory and map, which this "
                                "scenario does not have");
  }
  RequirePositiveDefinite(s.control_noise_cov, prefix, "the control noise covariance Q_u");
  RequirePositiveDefinite(s.sensor.noise_cov, prefix, "the measurement noise covariance R");
  if (!(s.sensor.pd_max > 0.0)) {
    throw std::invalid_argument(prefix +
                                "detection probability 0 (option detection_probability): no "
                                "detection carries information and the bound is infinite");
  }
  if (p.detection_model == DetectionModel::kConditioned) {
    for (const datasets::ScenarioStep& step : s.steps) {
      if (step.origin.size() != step.data.measurements.size()) {
        throw std::invalid_argument(prefix +
                                    "detection_model=conditioned needs the origin labels, which "
                                    "this scenario does not have (use detection_model=irf)");
      }
    }
  }
}

// The control that moves the unicycle from `a` to `b` in dt: the exact inverse of the velocity
// model (the chord at half the heading change, reference/ceres/velocity_odometry_factor.h).
Control TrueVelocityControl(const Pose& a, const Pose& b, double dt) {
  const double c = std::cos(a(2));
  const double s = std::sin(a(2));
  const double bx = c * (b(0) - a(0)) + s * (b(1) - a(1));
  const double by = -s * (b(0) - a(0)) + c * (b(1) - a(1));
  const double dtheta = b(2) - a(2);
  const double h = dtheta / 2.0;
  const double along = bx * std::cos(h) + by * std::sin(h);
  const double ratio = std::abs(h) < 1e-4 ? 1.0 + h * h / 6.0 : h / std::sin(h);
  return {along * ratio / dt, dtheta / dt};
}

std::vector<MotionBlock> StepMotion(const models::MotionModel& motion, const StepData& data, Pose x,
                                    const Pose* end, bool velocity) {
  if (velocity && end != nullptr && data.times.size() == 2 && data.controls.size() == 1) {
    // One sub-interval of the unicycle: the Jacobians at the true control, which the true poses
    // determine, rather than at the recorded (noisy) odometry.
    const double dt = data.times[1] - data.times[0];
    if (dt > 0.0) {
      const models::MotionJacobians j = motion.Jacobians(x, TrueVelocityControl(x, *end, dt), dt);
      return {{j.fx, j.fu}};
    }
  }
  std::vector<MotionBlock> blocks;
  for (std::size_t i = 0; i + 1 < data.times.size() && i < data.controls.size(); ++i) {
    const double dt = data.times[i + 1] - data.times[i];
    const models::MotionJacobians j = motion.Jacobians(x, data.controls[i], dt);
    blocks.push_back({j.fx, j.fu});
    x = motion.Predict(x, data.controls[i], dt);
  }
  return blocks;
}

// The reduction factors by detection probability, each integral computed once per run.
class ReductionFactors {
 public:
  ReductionFactors(const datasets::Scenario& s, const PcrbParams& p, std::uint64_t seed)
      : settings_{1.0, WhitenedClutterDensity(s.sensor), p.gate_sigma, p.irf_samples},
        seed_(seed) {}

  double For(double pd) {
    auto it = cache_.find(pd);
    if (it != cache_.end()) return it->second;
    ReductionSettings s = settings_;
    s.detection_probability = pd;
    return cache_[pd] = InformationReductionFactor(s, seed_);
  }

 private:
  ReductionSettings settings_;
  std::uint64_t seed_;
  std::map<double, double> cache_;
};

bool AddDetection(const Pose& x, const Landmark& m, int index, const Mat2& r, double scale,
                  std::vector<Detection>& out) {
  if (!(scale > 0.0) || (m - x.head<2>()).norm() <= 0.0) return false;
  const models::RangeBearingJacobians j = models::MeasurementJacobians(x, m);
  out.push_back({index, j.hx, j.hm, r / scale});
  return true;
}

std::vector<Detection> StepDetections(const datasets::Scenario& s, std::size_t k,
                                      const PcrbParams& p, ReductionFactors& factors) {
  std::vector<Detection> out;
  const Pose& x = s.truth.poses[k];
  const Mat2& r = s.sensor.noise_cov;
  const auto landmarks = static_cast<int>(s.truth.landmarks.size());
  if (p.detection_model == DetectionModel::kConditioned) {
    const datasets::ScenarioStep& step = s.steps[k];
    for (int origin : step.origin) {
      if (origin < 0 || origin >= landmarks) continue;  // clutter or an unidentified detection
      AddDetection(x, s.truth.landmarks[static_cast<std::size_t>(origin)], origin, r,
                   factors.For(1.0), out);
    }
    return out;
  }
  const models::FovView view(s.sensor, x);
  for (int i = 0; i < landmarks; ++i) {
    const Landmark& m = s.truth.landmarks[static_cast<std::size_t>(i)];
    const double pd = view.DetectionProbability(m);
    if (pd > 0.0) AddDetection(x, m, i, r, factors.For(pd), out);
  }
  return out;
}

}  // namespace

double WhitenedClutterDensity(const models::SensorModel& sensor) {
  const double box = 2.0 * sensor.fov_half_angle * sensor.fov_range;
  return sensor.clutter_rate / box * std::sqrt(sensor.noise_cov.determinant());
}

LinearisedSlam Linearise(const datasets::Scenario& scenario, const PcrbParams& params,
                         std::uint64_t stream_seed, const std::string& who) {
  const std::string prefix = Prefix(who, scenario);
  CheckScenario(scenario, params, prefix);
  LinearisedSlam model;
  model.control_noise_cov = scenario.control_noise_cov;
  model.landmarks = static_cast<int>(scenario.truth.landmarks.size());
  const std::unique_ptr<models::MotionModel> motion = scenario.MakeMotionModel();
  ReductionFactors factors(scenario, params, stream_seed);
  model.steps.reserve(scenario.steps.size());
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    const Pose start = k == 0 ? scenario.initial_pose : scenario.truth.poses[k - 1];
    LinearStep step;
    step.motion = StepMotion(*motion, scenario.steps[k].data, start, &scenario.truth.poses[k],
                             scenario.motion == datasets::MotionKind::kVelocity);
    step.detections = StepDetections(scenario, k, params, factors);
    model.steps.push_back(std::move(step));
  }
  return model;
}

}  // namespace phdslam::reference::pcrb
