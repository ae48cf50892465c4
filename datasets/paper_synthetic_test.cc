#include "datasets/paper_synthetic.h"

#include <gtest/gtest.h>
#include <matio.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <numbers>
#include <stdexcept>
#include <string>

#include "datasets/data_dir.h"
#include "datasets/scenario_check.h"
#include "datasets/test_data_sets.h"
#include "datasets/test_temp_dir.h"
#include "src/core/angles.h"
#include "src/models/range_bearing_model.h"
#include "src/models/velocity_motion_model.h"

namespace phdslam::datasets {
namespace {

class PaperSyntheticTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    env_ =
        new PaperSyntheticEnvironment(LoadPaperSyntheticEnvironment(testing::SyntheticDataDir()));
    const auto start = std::chrono::steady_clock::now();
    seed1_ = new Scenario(MakePaperSyntheticScenario(*env_, 1));
    const auto stop = std::chrono::steady_clock::now();
    std::cout << "[ info ] generating the 4000-step paper scenario (seed 1) took "
              << std::chrono::duration<double, std::milli>(stop - start).count() << " ms\n";
  }
  static void TearDownTestSuite() {
    delete seed1_;
    delete env_;
    seed1_ = nullptr;
    env_ = nullptr;
  }

  /// True when m is inside the FOV of x (inclusive tests of docs/algorithms/models.md section 4.1).
  static bool Visible(const Pose& x, const Landmark& m, const SyntheticOptions& o) {
    const double dx = m(0) - x(0);
    const double dy = m(1) - x(1);
    return dx * dx + dy * dy <= o.fov_range * o.fov_range &&
           std::abs(WrapAngle(std::atan2(dy, dx) - x(2))) <= o.fov_half_angle;
  }

  static PaperSyntheticEnvironment* env_;
  static Scenario* seed1_;
};
PaperSyntheticEnvironment* PaperSyntheticTest::env_ = nullptr;
Scenario* PaperSyntheticTest::seed1_ = nullptr;

TEST_F(PaperSyntheticTest, EnvironmentHasThePaperShapes) {
  EXPECT_EQ(env_->landmarks.size(), 160u);
  EXPECT_EQ(env_->true_controls.size(), 4000u);
  EXPECT_EQ(env_->initial_pose(0), 300.0);
  EXPECT_EQ(env_->initial_pose(1), 400.0);
  EXPECT_NEAR(env_->initial_pose(2), DegToRad(-5.0), 1e-15);
  for (const Control& u : env_->true_controls) EXPECT_NE(u(1), 0.0);
}

TEST_F(PaperSyntheticTest, TruthIsTheMotionModelOnNoiseFreeControls) {
  const Scenario& s = *seed1_;
  ASSERT_EQ(s.steps.size(), 4000u);
  ASSERT_EQ(s.truth.poses.size(), 4000u);
  EXPECT_EQ(s.truth.poses[0](0), 300.0);
  EXPECT_EQ(s.truth.poses[0](1), 400.0);
  EXPECT_NEAR(s.truth.poses[0](2), DegToRad(-5.0), 1e-15);
  EXPECT_EQ(s.initial_pose, s.truth.poses[0]);
  const models::VelocityMotionModel f;
  for (std::size_t k = 1; k < s.truth.poses.size(); ++k) {
    ASSERT_EQ(s.truth.poses[k], f.Predict(s.truth.poses[k - 1], env_->true_controls[k - 1], 1.0))
        << "step " << k;
  }
  // Hand check of step 2: x + v/w (sin(th + w) - sin th), ...
  const Control u = env_->true_controls[0];
  const double th = DegToRad(-5.0);
  EXPECT_NEAR(s.truth.poses[1](0), 300.0 + u(0) / u(1) * (std::sin(th + u(1)) - std::sin(th)),
              1e-9);
  EXPECT_NEAR(s.truth.poses[1](1), 400.0 + u(0) / u(1) * (std::cos(th) - std::cos(th + u(1))),
              1e-9);
  EXPECT_NEAR(s.truth.poses[1](2), th + u(1), 1e-15);
  EXPECT_EQ(s.truth.landmarks, env_->landmarks);
}

TEST_F(PaperSyntheticTest, ScenarioFieldsFollowTheOptions) {
  const Scenario& s = *seed1_;
  const SyntheticOptions o;
  EXPECT_EQ(s.name, "paper-synthetic");
  EXPECT_EQ(s.seed, 1u);
  EXPECT_EQ(s.motion, MotionKind::kVelocity);
  EXPECT_EQ(s.control_noise_cov, o.control_noise_cov);
  EXPECT_NEAR(o.control_noise_cov(1, 1), 7.6154e-5, 1e-9);
  EXPECT_NEAR(o.measurement_noise_cov(1, 1), 2.7416e-5, 1e-9);
  EXPECT_EQ(s.sensor.noise_cov, o.measurement_noise_cov);
  EXPECT_EQ(s.sensor.profile, models::DetectionProfile::kConstant);
  EXPECT_EQ(s.sensor.pd_max, 0.95);
  EXPECT_EQ(s.sensor.pd_nominal, 0.95);
  EXPECT_EQ(s.sensor.clutter_rate, 5.0);
  EXPECT_EQ(s.sensor.fov_range, 150.0);
  EXPECT_EQ(s.sensor.range_buffer, 10.0);
  EXPECT_NEAR(s.sensor.ClutterIntensity(), 1.4147e-4, 1e-8);
  EXPECT_NO_THROW(CheckScenario(s, "paper-synthetic seed 1"));
}

TEST_F(PaperSyntheticTest, TimesAndControlsFollowTheStepLayout) {
  const Scenario& s = *seed1_;
  ASSERT_EQ(s.steps[0].data.times, std::vector<double>{0.0});
  EXPECT_TRUE(s.steps[0].data.controls.empty());
  for (std::size_t k = 1; k < s.steps.size(); ++k) {
    const StepData& d = s.steps[k].data;
    ASSERT_EQ(d.times, (std::vector<double>{static_cast<double>(k - 1), static_cast<double>(k)}));
    ASSERT_EQ(d.controls.size(), 1u);
    ASSERT_EQ(s.steps[k].origin.size(), d.measurements.size());
  }
}

TEST_F(PaperSyntheticTest, OdometryIsTrueControlPlusQuNoise) {
  const Scenario& s = *seed1_;
  const Mat2 qu = SyntheticOptions().control_noise_cov;
  Vec2 sum = Vec2::Zero();
  Vec2 sum2 = Vec2::Zero();
  const double n = static_cast<double>(s.steps.size() - 1);
  for (std::size_t k = 1; k < s.steps.size(); ++k) {
    const Vec2 e = s.steps[k].data.controls[0] - env_->true_controls[k - 1];
    sum += e;
    sum2 += e.cwiseProduct(e);
  }
  for (int i = 0; i < 2; ++i) {
    const double sigma = std::sqrt(qu(i, i));
    // Mean within 5 standard errors of 0; variance within 5 standard errors (sqrt(2/n)) of Q_u.
    EXPECT_NEAR(sum(i) / n, 0.0, 5.0 * sigma / std::sqrt(n)) << i;
    EXPECT_NEAR(sum2(i) / n / qu(i, i), 1.0, 5.0 * std::sqrt(2.0 / n)) << i;
  }
}

TEST_F(PaperSyntheticTest, MeasurementCountsMatchTheirExpectation) {
  const Scenario& s = *seed1_;
  const SyntheticOptions o;
  const double pd = o.detection_probability;
  const double lambda = o.clutter_rate;
  double expected = 0.0;
  double variance = 0.0;
  double visible_total = 0.0;
  double measured = 0.0;
  double clutter = 0.0;
  double detections = 0.0;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    double visible = 0.0;
    for (const Landmark& m : env_->landmarks) visible += Visible(s.truth.poses[k], m, o) ? 1 : 0;
    visible_total += visible;
    expected += pd * (visible + lambda);
    // Binomial(visible, pD) detections plus Poisson(lambda pD) surviving clutter.
    variance += visible * pd * (1.0 - pd) + lambda * pd;
    measured += static_cast<double>(s.steps[k].data.measurements.size());
    for (int origin : s.steps[k].origin) (origin == kClutter ? clutter : detections) += 1.0;
  }
  const double n = static_cast<double>(s.steps.size());
  std::cout << "[ info ] seed 1: mean visible landmarks " << visible_total / n
            << ", mean measurements " << measured / n << " (expected " << expected / n
            << "), landmark detections " << detections / n << ", clutter " << clutter / n
            << " per step\n";
  // Steps are independent given the truth: 5 standard deviations of the mean.
  EXPECT_NEAR(measured / n, expected / n, 5.0 * std::sqrt(variance) / n);
  EXPECT_NEAR(clutter / n, lambda * pd, 5.0 * std::sqrt(lambda * pd / n));
  EXPECT_NEAR(detections / visible_total, pd, 5.0 * std::sqrt(pd * (1.0 - pd) / visible_total));
}

TEST_F(PaperSyntheticTest, DetectionsComeFromVisibleLandmarksWithRNoise) {
  const Scenario& s = *seed1_;
  const SyntheticOptions o;
  Vec2 sum = Vec2::Zero();
  Vec2 sum2 = Vec2::Zero();
  double n = 0.0;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    const ScenarioStep& step = s.steps[k];
    int previous_landmark = -1;
    for (std::size_t j = 0; j < step.origin.size(); ++j) {
      const int origin = step.origin[j];
      if (origin == kClutter) {
        previous_landmark = std::numeric_limits<int>::max();  // clutter follows the landmarks
        continue;
      }
      ASSERT_GT(origin, previous_landmark)
          << "landmarks in index order, before clutter, step " << k;
      previous_landmark = origin;
      const Landmark& m = env_->landmarks[static_cast<std::size_t>(origin)];
      ASSERT_TRUE(Visible(s.truth.poses[k], m, o)) << "step " << k << " landmark " << origin;
      const Measurement h = models::PredictMeasurement(s.truth.poses[k], m);
      const Vec2 e(step.data.measurements[j](0) - h(0),
                   WrapAngle(step.data.measurements[j](1) - h(1)));
      sum += e;
      sum2 += e.cwiseProduct(e);
      n += 1.0;
    }
  }
  for (int i = 0; i < 2; ++i) {
    const double var = o.measurement_noise_cov(i, i);
    EXPECT_NEAR(sum(i) / n, 0.0, 5.0 * std::sqrt(var / n)) << i;
    EXPECT_NEAR(sum2(i) / n / var, 1.0, 5.0 * std::sqrt(2.0 / n)) << i;
  }
}

TEST_F(PaperSyntheticTest, BearingsWrappedAndClutterInsideTheNoisyFov) {
  const Scenario& s = *seed1_;
  const SyntheticOptions o;
  const double range_sigma = std::sqrt(o.measurement_noise_cov(0, 0));
  const double bearing_sigma = std::sqrt(o.measurement_noise_cov(1, 1));
  double clutter = 0.0;
  double clutter_range_sum = 0.0;
  for (const ScenarioStep& step : s.steps) {
    for (std::size_t j = 0; j < step.origin.size(); ++j) {
      const Measurement& z = step.data.measurements[j];
      ASSERT_GE(z(1), -std::numbers::pi);
      ASSERT_LE(z(1), std::numbers::pi);
      if (step.origin[j] != kClutter) continue;
      // Range uniform on [0, R] plus N(0, 0.8^2) noise; bearing uniform on [-90, 90] deg plus
      // noise: 6 sigma bounds.
      ASSERT_GE(z(0), -6.0 * range_sigma);
      ASSERT_LE(z(0), o.fov_range + 6.0 * range_sigma);
      ASSERT_LE(std::abs(z(1)), o.fov_half_angle + 6.0 * bearing_sigma);
      clutter += 1.0;
      clutter_range_sum += z(0);
    }
  }
  // Uniform in range (not in area): mean range R / 2, standard error R / sqrt(12 n).
  EXPECT_NEAR(clutter_range_sum / clutter, o.fov_range / 2.0,
              5.0 * o.fov_range / std::sqrt(12.0 * clutter));
}

TEST_F(PaperSyntheticTest, SameSeedIsBitIdenticalAndSeedsDiffer) {
  const Scenario again = MakePaperSyntheticScenario(*env_, 1);
  const Scenario other = MakePaperSyntheticScenario(*env_, 2);
  ASSERT_EQ(again.steps.size(), seed1_->steps.size());
  bool any_difference = false;
  for (std::size_t k = 0; k < again.steps.size(); ++k) {
    const ScenarioStep& a = again.steps[k];
    const ScenarioStep& b = seed1_->steps[k];
    ASSERT_EQ(a.data.times, b.data.times);
    ASSERT_EQ(a.data.controls, b.data.controls);
    ASSERT_EQ(a.data.measurements, b.data.measurements);
    ASSERT_EQ(a.origin, b.origin);
    const ScenarioStep& c = other.steps[k];
    any_difference = any_difference || c.data.measurements != b.data.measurements ||
                     c.data.controls != b.data.controls;
  }
  EXPECT_EQ(again.truth.poses, seed1_->truth.poses);
  EXPECT_TRUE(any_difference);
  EXPECT_EQ(other.truth.poses, seed1_->truth.poses);  // the truth does not depend on the seed
  EXPECT_EQ(other.seed, 2u);
}

TEST_F(PaperSyntheticTest, ShorterRunIsAPrefix) {
  SyntheticOptions o;
  o.steps = 25;
  const Scenario s = MakePaperSyntheticScenario(*env_, 1, o);
  ASSERT_EQ(s.steps.size(), 25u);
  ASSERT_EQ(s.truth.poses.size(), 25u);
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    EXPECT_EQ(s.steps[k].data.measurements, seed1_->steps[k].data.measurements);
    EXPECT_EQ(s.steps[k].data.controls, seed1_->steps[k].data.controls);
  }
}

TEST_F(PaperSyntheticTest, NoiseFreeFullDetectionGivesExactMeasurements) {
  SyntheticOptions o;
  o.steps = 200;
  o.detection_probability = 1.0;
  o.clutter_rate = 0.0;
  o.measurement_noise_cov.setZero();
  o.control_noise_cov.setZero();
  const Scenario s = MakePaperSyntheticScenario(*env_, 7, o);
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    std::vector<int> visible;
    for (std::size_t i = 0; i < env_->landmarks.size(); ++i) {
      if (Visible(s.truth.poses[k], env_->landmarks[i], o)) visible.push_back(static_cast<int>(i));
    }
    ASSERT_EQ(s.steps[k].origin, visible) << "step " << k;
    for (std::size_t j = 0; j < visible.size(); ++j) {
      const auto& m = env_->landmarks[static_cast<std::size_t>(visible[j])];
      EXPECT_EQ(s.steps[k].data.measurements[j], models::PredictMeasurement(s.truth.poses[k], m));
    }
    if (k > 0) {
      EXPECT_EQ(s.steps[k].data.controls[0], env_->true_controls[k - 1]);
    }
  }
}

TEST_F(PaperSyntheticTest, InvalidOptionsNameTheField) {
  const auto error = [&](const SyntheticOptions& o) {
    try {
      (void)MakePaperSyntheticScenario(*env_, 1, o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  SyntheticOptions o;
  o.detection_probability = 0.0;
  EXPECT_NE(error(o).find("detection_probability"), std::string::npos);
  o = SyntheticOptions();
  o.clutter_rate = -1.0;
  EXPECT_NE(error(o).find("clutter_rate"), std::string::npos);
  o.clutter_rate = 1e9;  // within the double range, far beyond any sensor
  EXPECT_NE(error(o).find("clutter_rate"), std::string::npos);
  EXPECT_NE(error(o).find("1000"), std::string::npos);
  o = SyntheticOptions();
  o.steps = 4001;
  EXPECT_NE(error(o).find("steps"), std::string::npos);
  o = SyntheticOptions();
  o.steps = -1;
  EXPECT_NE(error(o).find("steps"), std::string::npos);
  o = SyntheticOptions();
  o.measurement_noise_cov(0, 0) = -1.0;
  EXPECT_NE(error(o).find("measurement_noise_cov"), std::string::npos);
  o = SyntheticOptions();
  o.fov_half_angle = 4.0;
  EXPECT_NE(error(o).find("fov_half_angle"), std::string::npos);
}

TEST(PaperSyntheticEnvironmentLoader, ErrorsNameFileAndVariable) {
  const auto dir = testing::FreshTestDir();
  try {
    (void)LoadPaperSyntheticEnvironment(dir);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("Environment_SLAM.mat"), std::string::npos) << e.what();
  }
  std::filesystem::create_directories(dir / "phdslam3-synthetic");
  const auto path = dir / "phdslam3-synthetic" / "Environment_SLAM.mat";
  {
    mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5);
    ASSERT_NE(mat, nullptr);
    double lm[5] = {1, 2, 3, 4, 5};
    size_t lm_dims[2] = {1, 5};
    matvar_t* v =
        Mat_VarCreate("Landmark_Groundtruth", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, lm_dims, lm, 0);
    Mat_VarWrite(mat, v, MAT_COMPRESSION_NONE);
    Mat_VarFree(v);
    double u[6] = {1, 0.1, 1, 0.1, 1, 0.1};
    size_t u_dims[2] = {3, 2};  // wrong: must be 2 x K
    v = Mat_VarCreate("Robot_Control", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, u_dims, u, 0);
    Mat_VarWrite(mat, v, MAT_COMPRESSION_NONE);
    Mat_VarFree(v);
    Mat_Close(mat);
  }
  try {
    (void)LoadPaperSyntheticEnvironment(dir);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("Robot_Control"), std::string::npos) << message;
    EXPECT_NE(message.find("3 x 2"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace phdslam::datasets
