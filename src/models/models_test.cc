#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "src/core/angles.h"
#include "src/models/car_motion_model.h"
#include "src/models/pose_propagation.h"
#include "src/models/range_bearing_model.h"
#include "src/models/sensor_model.h"
#include "src/models/velocity_motion_model.h"
#include "src/testing/jacobian_check.h"

namespace phdslam::models {
namespace {

using phdslam::testing::ExpectJacobianNear;
using phdslam::testing::ExpectSymmetricPositiveDefinite;

TEST(VelocityMotionModel, JacobiansMatchFiniteDifferences) {
  const VelocityMotionModel f;
  for (const Control& u : {Control(1.0, 0.01), Control(0.9, -0.0172), Control(1.1, 0.3)}) {
    const Pose x(300.0, 400.0, DegToRad(-5.0));
    const auto j = f.Jacobians(x, u, 1.0);
    ExpectJacobianNear<3, 3>(
        j.fx, [&](const Vec3& xx) { return f.Predict(xx, u, 1.0); }, x);
    ExpectJacobianNear<3, 2>(
        j.fu, [&](const Vec2& uu) { return f.Predict(x, uu, 1.0); }, u, 1e-5);
  }
}

// One sub-interval: f(x) and Fx P Fx^T + Fu Q_u Fu^T; a second one chains from that result; a
// single time stamp changes nothing.
TEST(PropagatePoseGaussian, IsTheLinearisedPredictionPerSubInterval) {
  const VelocityMotionModel f;
  const Mat2 qu = Vec2(0.04, 1e-4).asDiagonal();
  const Pose x(1.0, -2.0, 0.4);
  Mat3 p;
  p << 0.3, 0.01, 0.002, 0.01, 0.2, -0.001, 0.002, -0.001, 0.01;
  StepData step;
  step.times = {0.0, 0.5, 1.5};
  step.controls = {Control(1.2, 0.1), Control(0.8, -0.3)};
  const auto j0 = f.Jacobians(x, step.controls[0], 0.5);
  const Pose x1 = f.Predict(x, step.controls[0], 0.5);
  const Mat3 p1 = j0.fx * p * j0.fx.transpose() + j0.fu * qu * j0.fu.transpose();
  const auto j1 = f.Jacobians(x1, step.controls[1], 1.0);
  const Pose x2 = f.Predict(x1, step.controls[1], 1.0);
  const Mat3 p2 = j1.fx * p1 * j1.fx.transpose() + j1.fu * qu * j1.fu.transpose();
  Pose mean = x;
  Mat3 cov = p;
  PropagatePoseGaussian(f, qu, step, mean, cov);
  EXPECT_LT((mean - x2).norm(), 1e-12);
  EXPECT_LT((cov - p2).norm(), 1e-12);
  EXPECT_EQ(cov, cov.transpose());
  ExpectSymmetricPositiveDefinite(cov);

  StepData still;
  still.times = {3.0};
  mean = x;
  cov = p;
  PropagatePoseGaussian(f, qu, still, mean, cov);
  EXPECT_EQ(mean, x);
  EXPECT_EQ(cov, p);
}

TEST(VelocityMotionModel, StraightLineLimitIsContinuous) {
  const VelocityMotionModel f;
  const Pose x(1.0, 2.0, 0.7);
  const Pose p0 = f.Predict(x, Control(1.0, 0.0), 2.0);
  const Pose p1 = f.Predict(x, Control(1.0, 1e-7), 2.0);
  EXPECT_NEAR((p0 - p1).norm(), 0.0, 1e-6);
  EXPECT_NEAR(p0(0), 1.0 + 2.0 * std::cos(0.7), 1e-12);
  const auto j0 = f.Jacobians(x, Control(1.0, 0.0), 2.0);
  const auto j1 = f.Jacobians(x, Control(1.0, 1e-6), 2.0);
  EXPECT_LT((j0.fx - j1.fx).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_LT((j0.fu - j1.fu).cwiseAbs().maxCoeff(), 1e-4);
  // The straight-line Jacobians are exact derivatives of the straight-line model at omega = 0
  // along the pose; the omega column is the limit of the turning model.
  ExpectJacobianNear<3, 3>(
      j0.fx, [&](const Vec3& xx) { return f.Predict(xx, Control(1, 0), 2); }, x);
}

TEST(CarMotionModel, PoseJacobianMatchesFiniteDifferencesAndControlJacobianIsTheReferenceOne) {
  const CarMotionModel f;
  const Pose x(-67.6493, -41.7142, DegToRad(35.5));
  const Control u(2.5, 0.1);
  const double dt = 0.025;
  const auto j = f.Jacobians(x, u, dt);
  ExpectJacobianNear<3, 3>(
      j.fx, [&](const Vec3& xx) { return f.Predict(xx, u, dt); }, x);
  // The reference Fu is deliberately approximate (docs/algorithms/models.md section 2.3): with
  // alpha = 0 the v_e column is exact, and the alpha column equals the derivative with v_c held
  // fixed.
  const Control u0(2.5, 0.0);
  const auto j0 = f.Jacobians(x, u0, dt);
  const auto fv = [&](const Vec2& uu) { return f.Predict(x, uu, dt); };
  const Eigen::Matrix<double, 3, 2> num = phdslam::testing::NumericJacobian<3, 2>(fv, u0);
  EXPECT_NEAR(j0.fu(0, 0), num(0, 0), 1e-8);
  EXPECT_NEAR(j0.fu(1, 0), num(1, 0), 1e-8);
  EXPECT_NEAR(j0.fu(2, 0), num(2, 0), 1e-8);
  EXPECT_NEAR(j0.fu(2, 1), dt * 2.5 / 2.83, 1e-12);
}

TEST(RangeBearingModel, JacobiansMatchFiniteDifferences) {
  const Pose x(3.0, -1.0, 2.9);
  for (const Landmark& m : {Landmark(10.0, 4.0), Landmark(-20.0, 1.0), Landmark(3.5, -40.0)}) {
    const auto j = MeasurementJacobians(x, m);
    ExpectJacobianNear<2, 3>(j.hx, [&](const Vec3& xx) { return PredictMeasurement(xx, m); }, x,
                             1e-6, {1});
    ExpectJacobianNear<2, 2>(j.hm, [&](const Vec2& mm) { return PredictMeasurement(x, mm); }, m,
                             1e-6, {1});
  }
}

TEST(RangeBearingModel, InverseModelRoundTripsAndItsJacobianMatches) {
  const Pose x(3.0, -1.0, -2.0);
  const Measurement z(12.0, 0.4);
  const Landmark m = InverseMeasurement(x, z);
  const Measurement back = PredictMeasurement(x, m);
  EXPECT_NEAR(back(0), z(0), 1e-12);
  EXPECT_NEAR(back(1), z(1), 1e-12);
  ExpectJacobianNear<2, 2>(
      InverseMeasurementJacobian(x, z), [&](const Vec2& zz) { return InverseMeasurement(x, zz); },
      z);
  Mat2 r;
  r << 0.64, 0.0, 0.0, 2.7416e-5;
  ExpectSymmetricPositiveDefinite(BirthCovariance(x, z, r));
}

TEST(RangeBearingModel, BearingIsWrapped) {
  const Pose x(0.0, 0.0, 3.0);
  const Measurement z = PredictMeasurement(x, Landmark(-1.0, -0.1));
  EXPECT_LE(std::abs(z(1)), M_PI);
  EXPECT_NEAR(z(1), WrapAngle(std::atan2(-0.1, -1.0) - 3.0), 1e-15);
}

TEST(SensorModel, DetectionProbabilityAndFovAreInclusivePointTests) {
  SensorModel s;
  const Pose x(0.0, 0.0, 0.0);
  EXPECT_EQ(s.DetectionProbability(x, Landmark(150.0, 0.0)), 0.95);
  EXPECT_EQ(s.DetectionProbability(x, Landmark(150.001, 0.0)), 0.0);
  EXPECT_EQ(s.DetectionProbability(x, Landmark(-1.0, 0.0)), 0.0);
  EXPECT_TRUE(s.InEnlargedFov(x, Landmark(155.0, 0.0)));
  EXPECT_TRUE(s.InEnlargedFov(x, Landmark(-1.0, 10.0)));  // 95.7 deg < 100 deg
  EXPECT_FALSE(s.InEnlargedFov(x, Landmark(-1.0, 5.0)));  // 101.3 deg
  EXPECT_FALSE(s.InEnlargedFov(x, Landmark(161.0, 0.0)));
  s.profile = DetectionProfile::kLinearRange;
  s.pd_max = 0.7;
  s.fov_range = 50.0;
  EXPECT_NEAR(s.DetectionProbability(x, Landmark(25.0, 0.0)), 0.35, 1e-12);
  EXPECT_NEAR(SensorModel{}.ClutterIntensity(), 1.4147e-4, 1e-8);
  // A clutter-free sensor still gives the filters a positive intensity (its floor), and the floor
  // is far below the paper's rate.
  SensorModel clutter_free;
  clutter_free.clutter_rate = 0.0;
  EXPECT_GT(clutter_free.ClutterIntensity(), 0.0);
  EXPECT_NEAR(clutter_free.ClutterIntensity() / SensorModel{}.ClutterIntensity(),
              SensorModel::kMinFilterClutterRate / 5.0, 1e-15);
}

TEST(SensorModel, RangeBearingBoxClutterIntensityIsTheBoxDensity) {
  // The range-bearing-box kappa of docs/algorithms/models.md section 3.6 for the 3 m disc:
  // lambda_c / (3 * 2 pi), 0.0531 at lambda_c = 1 and 0.796 at 15, 1.5 times the sector-area
  // reading lambda_c / (9 pi).
  SensorModel s;
  s.fov_range = 3.0;
  s.fov_half_angle = std::numbers::pi;
  s.clutter_rate = 1.0;
  const double sector = s.ClutterIntensity();
  s.clutter_space = ClutterSpace::kRangeBearingBox;
  EXPECT_NEAR(s.ClutterIntensity(), 0.0531, 5e-5);
  EXPECT_NEAR(s.ClutterIntensity() / sector, 1.5, 1e-12);
  s.clutter_rate = 15.0;
  EXPECT_NEAR(s.ClutterIntensity(), 0.796, 5e-4);
}

TEST(RangeBearingModel, FusedPredictionEqualsTheSeparateFunctionsBitForBit) {
  const Pose x(3.0, -2.0, 2.9);
  for (const Landmark& m : {Landmark(10.0, 4.0), Landmark(-7.0, -1.0), Landmark(3.0, 8.5),
                            Landmark(-20.0, -2.0 + 1e-9)}) {
    const auto [z_hat, j] = PredictWithJacobians(x, m);
    const Measurement z_sep = PredictMeasurement(x, m);
    const RangeBearingJacobians j_sep = MeasurementJacobians(x, m);
    EXPECT_EQ(z_hat(0), z_sep(0));
    EXPECT_EQ(z_hat(1), z_sep(1));
    EXPECT_TRUE((j.hx.array() == j_sep.hx.array()).all());
    EXPECT_TRUE((j.hm.array() == j_sep.hm.array()).all());
  }
}

TEST(RangeBearingModel, FusedBirthEqualsTheSeparateFunctionsBitForBit) {
  Mat2 r;
  r << 0.64, 0.01, 0.01, 2.7e-5;
  for (const Pose& x : {Pose(3.0, -2.0, 2.9), Pose(-40.0, 7.5, -3.1), Pose(0.0, 0.0, 0.0)}) {
    for (const Measurement& z : {Measurement(12.0, 0.4), Measurement(149.0, -1.5),
                                 Measurement(0.5, 3.0), Measurement(60.0, -0.001)}) {
      const BirthGaussian birth = BirthFromMeasurement(x, z, r);
      const Landmark mean = InverseMeasurement(x, z);
      const Mat2 cov = BirthCovariance(x, z, r);
      EXPECT_EQ(birth.mean(0), mean(0));
      EXPECT_EQ(birth.mean(1), mean(1));
      EXPECT_TRUE((birth.cov.array() == cov.array()).all());
    }
  }
}

TEST(SensorModel, LogDetectionTermsFollowTheLastPd) {
  LogDetectionTerms terms;
  for (const double pd : {0.95, 0.95, 0.3, 0.0, 1.0, 0.7}) {
    terms.Set(pd);
    EXPECT_EQ(terms.log_pd(), std::log(pd));
    EXPECT_EQ(terms.log_miss(), std::log1p(-pd));
  }
}

}  // namespace
}  // namespace phdslam::models
