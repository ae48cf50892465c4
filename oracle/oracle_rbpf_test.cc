#include "oracle/oracle_rbpf.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "datasets/scenario.h"
#include "datasets/scenario_generator.h"
#include "src/core/angles.h"
#include "src/core/random.h"
#include "src/models/pose_propagation.h"
#include "src/models/range_bearing_model.h"
#include "src/models/velocity_motion_model.h"

namespace phdslam::oracle {
namespace {

// A dozen landmarks along a 100-step path, low noise, no clutter.
datasets::Scenario SmallScenario(double clutter_rate, std::uint64_t seed) {
  datasets::GeneratorOptions o;
  o.steps = 100;
  o.landmarks = 12;
  o.corridor_half_width = 40.0;
  o.clutter_rate = clutter_rate;
  o.measurement_noise_cov = Vec2(0.05 * 0.05, std::pow(DegToRad(0.05), 2)).asDiagonal();
  o.control_noise_cov = Vec2(0.05 * 0.05, std::pow(DegToRad(0.05), 2)).asDiagonal();
  o.initial_pose = Pose(10.0, -20.0, 0.3);
  return datasets::GenerateScenario(o, seed);
}

struct RunResult {
  std::vector<filters::StepOutput> outputs;
  filters::MapEstimate map;
  std::vector<double> final_log_weights;
};

RunResult RunOracle(const datasets::Scenario& s, const OracleParams& params, std::uint64_t seed) {
  auto oracle = MakeOracle(s, params, seed);
  RunResult r;
  for (const auto& step : s.steps) r.outputs.push_back(oracle->Step(step.data));
  r.map = oracle->Map();
  for (const auto& p : oracle->particles()) r.final_log_weights.push_back(p.log_weight);
  return r;
}

// Gaussian log-density written out with an explicit inverse and determinant.
template <int N>
double HandLogNormal(const Eigen::Matrix<double, N, 1>& d, const Eigen::Matrix<double, N, N>& s) {
  return -0.5 * (N * std::log(2.0 * std::numbers::pi) + std::log(s.determinant()) +
                 d.dot(s.inverse() * d));
}

TEST(OracleRbpf, TracksTheTruthTightlyOnALowNoiseScenario) {
  const datasets::Scenario s = SmallScenario(0.0, 3);
  ASSERT_EQ(s.truth.landmarks.size(), 12u);
  for (int particles : {1, 5}) {
    OracleParams params;
    params.particles = particles;
    const RunResult r = RunOracle(s, params, 11);
    double max_position_error = 0.0;
    double max_heading_error = 0.0;
    for (std::size_t k = 0; k < s.steps.size(); ++k) {
      const Vec3 e = r.outputs[k].pose - s.truth.poses[k];
      max_position_error = std::max(max_position_error, e.head<2>().norm());
      max_heading_error = std::max(max_heading_error, std::abs(e(2)));
    }
    EXPECT_LT(max_position_error, 0.25) << "N = " << particles;
    EXPECT_LT(max_heading_error, DegToRad(0.2)) << "N = " << particles;
    // Every landmark that was measured is in the map, close to the truth.
    std::vector<bool> measured(s.truth.landmarks.size(), false);
    for (const auto& step : s.steps) {
      for (int o : step.origin) {
        if (o >= 0) measured[o] = true;
      }
    }
    std::size_t expected = 0;
    for (bool b : measured) expected += b ? 1 : 0;
    ASSERT_GT(expected, 6u);
    ASSERT_EQ(r.map.size(), expected);
    std::size_t slot = 0;
    for (std::size_t i = 0; i < measured.size(); ++i) {
      if (!measured[i]) continue;
      EXPECT_LT((r.map.means[slot] - s.truth.landmarks[i]).norm(), 0.3) << "landmark " << i;
      EXPECT_EQ(r.map.log_weights[slot], 0.0);
      ++slot;
    }
  }
}

TEST(OracleRbpf, ClutterMeasurementsChangeNothing) {
  const datasets::Scenario with_clutter = SmallScenario(5.0, 4);
  datasets::Scenario without = with_clutter;
  std::size_t clutter_count = 0;
  for (auto& step : without.steps) {
    datasets::ScenarioStep kept;
    kept.data.times = step.data.times;
    kept.data.controls = step.data.controls;
    for (std::size_t j = 0; j < step.origin.size(); ++j) {
      if (step.origin[j] == datasets::kClutter) {
        ++clutter_count;
        continue;
      }
      kept.data.measurements.push_back(step.data.measurements[j]);
      kept.origin.push_back(step.origin[j]);
    }
    step = kept;
  }
  ASSERT_GT(clutter_count, 100u);
  OracleParams params;
  params.particles = 10;
  const RunResult a = RunOracle(with_clutter, params, 5);
  const RunResult b = RunOracle(without, params, 5);
  bool resampled = false;
  for (std::size_t k = 0; k < with_clutter.steps.size(); ++k) {
    ASSERT_EQ(a.outputs[k].pose, b.outputs[k].pose) << "step " << k;
    ASSERT_EQ(a.outputs[k].diag.ess, b.outputs[k].diag.ess) << "step " << k;
    ASSERT_EQ(a.outputs[k].diag.resampled, b.outputs[k].diag.resampled) << "step " << k;
    resampled = resampled || a.outputs[k].diag.resampled;
    // The association of each landmark measurement is the same; clutter is never associated.
    const auto& origin = with_clutter.steps[k].origin;
    ASSERT_EQ(a.outputs[k].association.size(), origin.size());
    std::size_t jb = 0;
    for (std::size_t j = 0; j < origin.size(); ++j) {
      const Landmark& la = a.outputs[k].association[j];
      if (origin[j] == datasets::kClutter) {
        EXPECT_TRUE(la.hasNaN());
        continue;
      }
      const Landmark& lb = b.outputs[k].association[jb++];
      EXPECT_TRUE(la.hasNaN() ? lb.hasNaN() : la == lb);
    }
  }
  EXPECT_TRUE(resampled);
  ASSERT_EQ(a.map.size(), b.map.size());
  for (std::size_t i = 0; i < a.map.size(); ++i) {
    EXPECT_EQ(a.map.means[i], b.map.means[i]);
    EXPECT_EQ(a.map.covs[i], b.map.covs[i]);
  }
  EXPECT_EQ(a.final_log_weights, b.final_log_weights);
}

TEST(OracleRbpf, SameSeedGivesIdenticalResultsAndAnotherSeedDiffers) {
  const datasets::Scenario s = SmallScenario(5.0, 6);
  OracleParams params;
  params.particles = 8;
  const RunResult a = RunOracle(s, params, 21);
  const RunResult b = RunOracle(s, params, 21);
  const RunResult c = RunOracle(s, params, 22);
  bool differs = false;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    ASSERT_EQ(a.outputs[k].pose, b.outputs[k].pose);
    ASSERT_TRUE(a.outputs[k].pose_cov.has_value());
    ASSERT_EQ(*a.outputs[k].pose_cov, *b.outputs[k].pose_cov);
    differs = differs || a.outputs[k].pose != c.outputs[k].pose;
  }
  EXPECT_EQ(a.final_log_weights, b.final_log_weights);
  ASSERT_EQ(a.map.size(), b.map.size());
  for (std::size_t i = 0; i < a.map.size(); ++i) EXPECT_EQ(a.map.means[i], b.map.means[i]);
  EXPECT_TRUE(differs);
}

TEST(OracleRbpf, SingleParticleWeightIncrementEqualsTheHandComputation) {
  filters::EstimatorContext context;
  context.initial_pose = Pose(2.0, -1.0, 0.2);
  context.motion = std::make_shared<models::VelocityMotionModel>();
  context.control_noise_cov = Vec2(0.3, 2e-3).asDiagonal();
  context.sensor.noise_cov = Vec2(0.2, 1e-3).asDiagonal();
  OracleParams params;
  params.ipl_iterations = 1;  // the proposal is then one EKF update from the prior
  params.pose_regularisation = Vec3(1e-3, 2e-3, 1e-4).asDiagonal();
  const std::uint64_t seed = 77;

  // Step 0: a single time stamp, landmark 0 seen. Step 1: landmark 0 again, one clutter point and
  // the first sighting of landmark 1.
  datasets::StepData s0;
  s0.times = {0.0};
  s0.measurements = {Measurement(28.4, 0.12)};
  datasets::StepData s1;
  s1.times = {0.0, 1.0};
  s1.controls = {Control(1.5, 0.04)};
  s1.measurements = {Measurement(27.3, 0.07), Measurement(12.0, -0.5), Measurement(37.0, -0.9)};
  auto oracle_ptr = MakeOracle(context, {{0}, {0, datasets::kClutter, 1}}, params, seed);
  OracleRbpf& oracle = *oracle_ptr;
  oracle.Step(s0);
  ASSERT_EQ(oracle.particles()[0].log_weight, 0.0);  // nothing re-observed: no increment
  ASSERT_EQ(oracle.particles()[0].pose, context.initial_pose);
  const OracleLandmark lm0 = oracle.particles()[0].map.landmarks[0];
  ASSERT_TRUE(lm0.seen);
  EXPECT_LT(
      (lm0.mean - models::InverseMeasurement(context.initial_pose, s0.measurements[0])).norm(),
      1e-12);
  const filters::StepOutput out = oracle.Step(s1);

  // The stream: per step one uniform then three normals (N = 1, no resampling draws).
  RandomStream rng(seed);
  rng.Uniform();
  rng.Normal();
  rng.Normal();
  rng.Normal();
  rng.Uniform();
  Vec3 xi;
  for (int i = 0; i < 3; ++i) xi(i) = rng.Normal();  // in order: x, y, heading

  // Prediction from a zero covariance: Q_n, then one propagation (models_test checks it).
  Pose mu0 = context.initial_pose;
  Mat3 sigma0 = params.pose_regularisation;
  models::PropagatePoseGaussian(*context.motion, context.control_noise_cov, s1, mu0, sigma0);
  // One EKF update of the pose with the landmark's uncertainty in the measurement noise.
  const Mat2& r = context.sensor.noise_cov;
  const auto j0 = models::MeasurementJacobians(mu0, lm0.mean);
  Vec2 nu0 = s1.measurements[0] - models::PredictMeasurement(mu0, lm0.mean);
  nu0(1) = WrapAngle(nu0(1));
  const Mat2 s_pose = j0.hx * sigma0 * j0.hx.transpose() + j0.hm * lm0.cov * j0.hm.transpose() + r;
  const Mat32 k_pose = sigma0 * j0.hx.transpose() * s_pose.inverse();
  const Pose q_mean = mu0 + k_pose * nu0;
  const Mat3 q_cov = sigma0 - k_pose * s_pose * k_pose.transpose();
  const Mat3 q_chol = Eigen::LLT<Mat3>(q_cov).matrixL();
  const Pose x = q_mean + q_chol * xi;
  // Landmark likelihood at the sampled pose.
  const auto jx = models::MeasurementJacobians(x, lm0.mean);
  Vec2 nu = s1.measurements[0] - models::PredictMeasurement(x, lm0.mean);
  nu(1) = WrapAngle(nu(1));
  const Mat2 s_lm = jx.hm * lm0.cov * jx.hm.transpose() + r;
  const double expected = HandLogNormal<3>(x - mu0, sigma0) - HandLogNormal<3>(x - q_mean, q_cov) +
                          HandLogNormal<2>(nu, s_lm);

  const auto& p = oracle.particles()[0];
  EXPECT_NEAR(p.log_weight, expected, 1e-8 * std::max(1.0, std::abs(expected)));
  EXPECT_LT((p.pose - x).norm(), 1e-10);
  EXPECT_LT((out.pose - x).norm(), 1e-10);
  EXPECT_FALSE(out.pose_cov.has_value());
  // The landmark EKF update at the sampled pose.
  const Mat2 k_lm = lm0.cov * jx.hm.transpose() * s_lm.inverse();
  EXPECT_LT((p.map.landmarks[0].mean - (lm0.mean + k_lm * nu)).norm(), 1e-10);
  EXPECT_LT((p.map.landmarks[0].cov - (lm0.cov - k_lm * s_lm * k_lm.transpose())).norm(), 1e-10);
  // The first sighting: inverse model at the sampled pose.
  ASSERT_TRUE(p.map.landmarks[1].seen);
  EXPECT_LT((p.map.landmarks[1].mean - models::InverseMeasurement(x, s1.measurements[2])).norm(),
            1e-10);
  EXPECT_LT((p.map.landmarks[1].cov - models::BirthCovariance(x, s1.measurements[2], r)).norm(),
            1e-12);
  // Association: the updated landmark's prior mean; NaN for clutter and the first sighting.
  ASSERT_EQ(out.association.size(), 3u);
  EXPECT_EQ(out.association[0], lm0.mean);
  EXPECT_TRUE(out.association[1].hasNaN());
  EXPECT_TRUE(out.association[2].hasNaN());
  EXPECT_EQ(out.diag.map_components, 2);
  // Map: both landmarks in index order, log-weight 0.
  const filters::MapEstimate map = oracle.Map();
  ASSERT_EQ(map.size(), 2u);
  EXPECT_EQ(map.means[0], p.map.landmarks[0].mean);
  EXPECT_EQ(map.means[1], p.map.landmarks[1].mean);
  EXPECT_EQ(map.log_weights, std::vector<double>({0.0, 0.0}));
}

TEST(OracleRbpf, MapIsEmptyBeforeTheFirstStep) {
  const datasets::Scenario s = SmallScenario(0.0, 1);
  auto oracle = MakeOracle(s, {}, 1);
  EXPECT_EQ(oracle->Map().size(), 0u);
}

TEST(OracleRbpf, RejectsUnknownOriginsAndMismatchedSteps) {
  datasets::Scenario s = SmallScenario(0.0, 2);
  s.name = "vp-like";
  datasets::Scenario unknown = s;
  for (auto& step : unknown.steps) {
    step.origin.assign(step.data.measurements.size(), datasets::kUnknownOrigin);
  }
  try {
    MakeOracle(unknown, {}, 1);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("vp-like"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Victoria Park"), std::string::npos) << e.what();
  }
  datasets::Scenario missing = s;
  missing.steps[3].origin.clear();
  ASSERT_FALSE(missing.steps[3].data.measurements.empty());
  EXPECT_THROW(MakeOracle(missing, {}, 1), std::invalid_argument);
  datasets::Scenario twice = s;
  twice.steps[3].origin.push_back(twice.steps[3].origin[0]);
  twice.steps[3].data.measurements.push_back(twice.steps[3].data.measurements[0]);
  EXPECT_THROW(MakeOracle(twice, {}, 1), std::invalid_argument);

  auto oracle = MakeOracle(s, {}, 1);
  datasets::StepData wrong = s.steps[0].data;
  wrong.measurements.push_back(Measurement(10.0, 0.0));
  EXPECT_THROW(oracle->Step(wrong), std::invalid_argument);
  for (const auto& step : s.steps) oracle->Step(step.data);
  EXPECT_THROW(oracle->Step(s.steps[0].data), std::invalid_argument);

  OracleParams bad;
  bad.particles = 0;
  EXPECT_THROW(MakeOracle(s, bad, 1), std::invalid_argument);
  bad = {};
  bad.ipl_iterations = 0;
  EXPECT_THROW(MakeOracle(s, bad, 1), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::oracle
