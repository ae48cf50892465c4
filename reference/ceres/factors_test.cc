#include <ceres/cost_function.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <memory>
#include <numbers>

#include "reference/ceres/odometry_factor.h"
#include "reference/ceres/odometry_increment.h"
#include "reference/ceres/range_bearing_factor.h"
#include "reference/ceres/velocity_odometry_factor.h"
#include "src/core/angles.h"
#include "src/models/car_motion_model.h"
#include "src/models/range_bearing_model.h"
#include "src/models/velocity_motion_model.h"
#include "src/testing/jacobian_check.h"

namespace phdslam::reference {
namespace {

using phdslam::testing::ExpectJacobianNear;
using phdslam::testing::ExpectSymmetricPositiveDefinite;
using RowMajor23 = Eigen::Matrix<double, 2, 3, Eigen::RowMajor>;
using RowMajor22 = Eigen::Matrix<double, 2, 2, Eigen::RowMajor>;
using RowMajor33 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

const Mat2 kQu = Vec2(0.64, 7.6154e-5).asDiagonal();
const Mat2 kR = Vec2(0.64, 2.7416e-5).asDiagonal();

datasets::StepData MakeStep(double t0, const std::vector<std::pair<double, Control>>& segments) {
  datasets::StepData s;
  s.times.push_back(t0);
  for (const auto& [dt, u] : segments) {
    s.controls.push_back(u);
    s.times.push_back(s.times.back() + dt);
  }
  return s;
}

Vec3 EvaluateOdometry(const ceres::CostFunction& f, const Pose& a, const Pose& b,
                      RowMajor33* ja = nullptr, RowMajor33* jb = nullptr) {
  const double* params[] = {a.data(), b.data()};
  Vec3 r;
  double* jac[] = {ja ? ja->data() : nullptr, jb ? jb->data() : nullptr};
  EXPECT_TRUE(f.Evaluate(params, r.data(), ja ? jac : nullptr));
  return r;
}

Vec2 EvaluateRangeBearing(const ceres::CostFunction& f, const Pose& x, const Landmark& m,
                          RowMajor23* jx = nullptr, RowMajor22* jm = nullptr) {
  const double* params[] = {x.data(), m.data()};
  Vec2 r;
  double* jac[] = {jx ? jx->data() : nullptr, jm ? jm->data() : nullptr};
  EXPECT_TRUE(f.Evaluate(params, r.data(), jx ? jac : nullptr));
  return r;
}

TEST(ComposeRelative, RelativePoseIsItsInverseAndHeadingsAreNotWrapped) {
  const Pose a(3.0, -2.0, 7.5);  // heading beyond 2 pi on purpose
  const Pose d(1.2, -0.4, 3.5);
  const Pose b = ComposeRelative(a, d);
  EXPECT_NEAR(b(2), 11.0, 1e-15);
  EXPECT_LT((RelativePose(a, b) - d).norm(), 1e-12);
  // Hand-computed: a quarter turn maps the body x axis onto the world y axis.
  const Pose q = ComposeRelative(Pose(1.0, 1.0, std::numbers::pi / 2), Pose(2.0, 0.5, 0.0));
  EXPECT_LT((q - Pose(0.5, 3.0, std::numbers::pi / 2)).norm(), 1e-12);
}

// The smoother's odometry rests on the models' equivariance: propagating from any pose equals
// composing that pose with the increment computed from the origin, and the covariance
// propagated from that pose is the origin's one rotated into the world frame.
void ExpectEquivariant(const models::MotionModel& model, const datasets::StepData& step) {
  const OdometryNoiseFloor no_floor{1e-30, 1e-30};
  const OdometryIncrement inc = ComposeStepOdometry(model, step, kQu, no_floor);
  ASSERT_TRUE(inc.propagated);
  for (const Pose& x0 : {Pose(300.0, 400.0, DegToRad(-5.0)), Pose(-67.6, -41.7, 8.3)}) {
    Pose x = x0;
    Mat3 p = Mat3::Zero();
    for (std::size_t i = 0; i < step.controls.size(); ++i) {
      const double dt = step.times[i + 1] - step.times[i];
      const models::MotionJacobians j = model.Jacobians(x, step.controls[i], dt);
      x = model.Predict(x, step.controls[i], dt);
      p = j.fx * p * j.fx.transpose() + j.fu * kQu * j.fu.transpose();
    }
    EXPECT_LT((ComposeRelative(x0, inc.delta) - x).norm(), 1e-9);
    Mat3 t = Mat3::Identity();
    t.topLeftCorner<2, 2>() << std::cos(x0(2)), -std::sin(x0(2)), std::sin(x0(2)), std::cos(x0(2));
    EXPECT_LT((t * inc.covariance * t.transpose() - p).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(ComposeStepOdometry, VelocityModelIsEquivariant) {
  ExpectEquivariant(models::VelocityMotionModel(), MakeStep(0.0, {{1.0, Control(1.0, 0.0172)}}));
  ExpectEquivariant(models::VelocityMotionModel(),
                    MakeStep(0.0, {{0.4, Control(1.0, 0.3)}, {0.6, Control(0.8, -0.2)}}));
}

TEST(ComposeStepOdometry, CarModelWithSubIntervalsIsEquivariant) {
  ExpectEquivariant(models::CarMotionModel(), MakeStep(10.0, {{0.025, Control(2.5, 0.1)},
                                                              {0.025, Control(2.6, 0.12)},
                                                              {0.030, Control(2.4, -0.05)}}));
}

TEST(ComposeStepOdometry, SingleVelocityIntervalHasRankTwoAndTheFloorFillsTheNullDirection) {
  const models::VelocityMotionModel model;
  const datasets::StepData step = MakeStep(0.0, {{1.0, Control(1.0, 0.01)}});
  const OdometryIncrement bare = ComposeStepOdometry(model, step, kQu, {1e-30, 1e-30});
  const Eigen::SelfAdjointEigenSolver<Mat3> es(bare.covariance);
  EXPECT_LT(es.eigenvalues()(0), 1e-15);
  EXPECT_GT(es.eigenvalues()(1), 1e-5);
  const OdometryNoiseFloor floor;
  const OdometryIncrement inc = ComposeStepOdometry(model, step, kQu, floor);
  const Mat3 added = inc.covariance - bare.covariance;
  EXPECT_NEAR(added(0, 0), floor.position_std * floor.position_std, 1e-15);
  EXPECT_NEAR(added(2, 2), floor.heading_std * floor.heading_std, 1e-18);
  ExpectSymmetricPositiveDefinite(inc.covariance);
  // The increment itself is the model's prediction from the origin.
  EXPECT_LT((inc.delta - model.Predict(Pose::Zero(), Control(1.0, 0.01), 1.0)).norm(), 1e-15);
}

TEST(ComposeStepOdometry, StepWithoutPropagationHasOnlyTheFloor) {
  datasets::StepData step;
  step.times = {0.0};
  const OdometryIncrement inc =
      ComposeStepOdometry(models::VelocityMotionModel(), step, kQu, OdometryNoiseFloor{});
  EXPECT_FALSE(inc.propagated);
  EXPECT_EQ(inc.delta, Pose::Zero());
  step.controls.push_back(Control(1.0, 0.0));  // a control without a time interval
  EXPECT_THROW(ComposeStepOdometry(models::VelocityMotionModel(), step, kQu, OdometryNoiseFloor{}),
               std::invalid_argument);
}

TEST(WhiteningMatrix, WhitensTheCovariance) {
  Mat3 cov;
  cov << 0.7, 0.1, 0.02, 0.1, 0.5, -0.03, 0.02, -0.03, 0.01;
  const Mat3 w = WhiteningMatrix<3>(cov);
  EXPECT_LT((w * cov * w.transpose() - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((w.transpose() * w - cov.inverse()).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_THROW(WhiteningMatrix<2>(Mat2::Zero()), std::invalid_argument);
}

TEST(OdometryFactor, ResidualIsTheWhitenedErrorInThePreviousFrame) {
  const models::VelocityMotionModel model;
  const OdometryIncrement inc = ComposeStepOdometry(
      model, MakeStep(0.0, {{1.0, Control(1.0, 0.01)}}), kQu, OdometryNoiseFloor{});
  const Mat3 w = WhiteningMatrix<3>(inc.covariance);
  const std::unique_ptr<ceres::CostFunction> f(OdometryFactor::Create(inc.delta, w));
  const Pose a(300.0, 400.0, 13.0);  // unwrapped heading
  const Pose b_pred = model.Predict(a, Control(1.0, 0.01), 1.0);
  EXPECT_LT(EvaluateOdometry(*f, a, b_pred).norm(), 1e-9);
  // Offsetting x_k by e in the frame of x_{k-1} gives the residual W e; a heading offset of
  // 2 pi is not wrapped away.
  const Pose e(0.3, -0.01, 2.0 * std::numbers::pi);
  const Pose b = ComposeRelative(a, RelativePose(a, b_pred) + e);
  EXPECT_LT((EvaluateOdometry(*f, a, b) - w * e).norm(), 1e-6);
}

TEST(OdometryFactor, JacobiansMatchFiniteDifferences) {
  const OdometryIncrement inc =
      ComposeStepOdometry(models::CarMotionModel(),
                          MakeStep(0.0, {{0.025, Control(2.5, 0.1)}, {0.025, Control(2.6, 0.2)}}),
                          Vec2(1.0, 4.8739e-3).asDiagonal(), OdometryNoiseFloor{});
  const std::unique_ptr<ceres::CostFunction> f(
      OdometryFactor::Create(inc.delta, WhiteningMatrix<3>(inc.covariance)));
  for (const auto& [a, b] : {std::pair{Pose(1.0, 2.0, 0.3), Pose(1.1, 2.05, 0.32)},
                             std::pair{Pose(-5.0, 7.0, -9.0), Pose(-4.0, 6.0, -8.0)}}) {
    RowMajor33 ja;
    RowMajor33 jb;
    EvaluateOdometry(*f, a, b, &ja, &jb);
    const Mat3 ja_col = ja;
    const Mat3 jb_col = jb;
    // The whitening is ~1e2-1e5 per unit, so compare relative to the entries' size.
    ExpectJacobianNear<3, 3>(
        ja_col, [&](const Vec3& aa) { return EvaluateOdometry(*f, aa, b); }, a, 1e-5);
    ExpectJacobianNear<3, 3>(
        jb_col, [&](const Vec3& bb) { return EvaluateOdometry(*f, a, bb); }, b, 1e-5);
  }
}

TEST(VelocityOdometryFactor, InvertsTheMotionModel) {
  const models::VelocityMotionModel model;
  const Mat2 w = WhiteningMatrix<2>(kQu);
  const Pose a(300.0, 400.0, 9.0);  // unwrapped heading
  for (const Control& u : {Control(1.0, 0.0172), Control(0.9, -0.3), Control(-1.19, 0.018),
                           Control(1.0, 0.0), Control(1.0, 1e-12), Control(1.0, 5e-5)}) {
    for (double dt : {1.0, 0.4}) {
      const Control odometry(1.1, 0.01);
      const std::unique_ptr<ceres::CostFunction> f(
          VelocityOdometryFactor::Create(odometry, dt, w, 1e-4));
      // Any pose the model reaches is explained exactly by its control: the residual is the
      // whitened control difference and the sideways term is zero.
      const Vec3 r = EvaluateOdometry(*f, a, model.Predict(a, u, dt));
      const Vec2 expected = w * (u - odometry);
      EXPECT_NEAR(r(0), expected(0), 1e-6 * (1.0 + std::abs(expected(0)))) << u.transpose();
      EXPECT_NEAR(r(1), expected(1), 1e-6 * (1.0 + std::abs(expected(1)))) << u.transpose();
      EXPECT_NEAR(r(2), 0.0, 1e-6) << u.transpose();
    }
  }
}

TEST(VelocityOdometryFactor, SidewaysOffsetIsTheLateralResidual) {
  const models::VelocityMotionModel model;
  const Control u(1.0, 0.2);
  const std::unique_ptr<ceres::CostFunction> f(
      VelocityOdometryFactor::Create(u, 1.0, WhiteningMatrix<2>(kQu), 0.01));
  const Pose a(1.0, 2.0, 0.5);
  const Pose b = model.Predict(a, u, 1.0);
  // Shift b by 3 mm perpendicular to the chord (direction theta_a + omega dt / 2).
  const double chord = a(2) + 0.1;
  const Pose shifted = b + Pose(-std::sin(chord), std::cos(chord), 0.0) * 3e-3;
  const Vec3 r = EvaluateOdometry(*f, a, shifted);
  EXPECT_NEAR(r(2), 0.3, 1e-9);  // 3 mm / 10 mm
  EXPECT_NEAR(r(0), 0.0, 1e-9);
  EXPECT_NEAR(r(1), 0.0, 1e-9);
}

TEST(VelocityOdometryFactor, HalfAngleRatioIsSmoothAcrossTheSeriesSwitch) {
  for (double h : {0.0, 5e-5, 9.999e-5, 1.0001e-4, 2e-4, 0.5}) {
    const double exact = h == 0.0 ? 1.0 : h / std::sin(h);
    EXPECT_NEAR(VelocityOdometryFactor::HalfAngleRatio(h), exact, 1e-15) << h;
  }
}

TEST(VelocityOdometryFactor, JacobiansMatchFiniteDifferences) {
  const std::unique_ptr<ceres::CostFunction> f(
      VelocityOdometryFactor::Create(Control(1.0, 0.01), 1.0, WhiteningMatrix<2>(kQu), 1e-2));
  for (const auto& [a, b] : {std::pair{Pose(1.0, 2.0, 0.3), Pose(1.9, 2.4, 0.32)},
                             std::pair{Pose(-5.0, 7.0, -9.0), Pose(-4.0, 6.0, -8.8)},
                             std::pair{Pose(0.0, 0.0, 0.0), Pose(1.0, 0.001, 1e-6)}}) {
    RowMajor33 ja;
    RowMajor33 jb;
    EvaluateOdometry(*f, a, b, &ja, &jb);
    const Mat3 ja_col = ja;
    const Mat3 jb_col = jb;
    ExpectJacobianNear<3, 3>(
        ja_col, [&](const Vec3& aa) { return EvaluateOdometry(*f, aa, b); }, a, 1e-5);
    ExpectJacobianNear<3, 3>(
        jb_col, [&](const Vec3& bb) { return EvaluateOdometry(*f, a, bb); }, b, 1e-5);
  }
}

TEST(RangeBearingFactor, ResidualWrapsOnlyTheBearing) {
  const Mat2 w = WhiteningMatrix<2>(kR);
  const Pose x(0.0, 0.0, 4.0 * std::numbers::pi);  // unwrapped heading
  const Landmark m(-10.0, 1e-3);                   // almost straight behind the world x axis
  const Measurement h = models::PredictMeasurement(x, m);
  ASSERT_GT(h(1), std::numbers::pi - 1e-3);
  // A measurement whose bearing sits on the other side of +-pi from the prediction.
  const Measurement z(h(0) - 0.5, WrapAngle(h(1) + 0.01));
  const std::unique_ptr<ceres::CostFunction> f(RangeBearingFactor::Create(z, w));
  const Vec2 expected = w * Vec2(0.5, -0.01);
  EXPECT_LT((EvaluateRangeBearing(*f, x, m) - expected).norm(), 1e-9);
}

TEST(RangeBearingFactor, JacobiansMatchFiniteDifferences) {
  const Mat2 w = WhiteningMatrix<2>(kR);
  const Measurement z(40.0, DegToRad(30.0));
  const std::unique_ptr<ceres::CostFunction> f(RangeBearingFactor::Create(z, w));
  for (const auto& [x, m] : {std::pair{Pose(300.0, 400.0, DegToRad(-5.0)), Landmark(330.0, 425.0)},
                             std::pair{Pose(0.0, 0.0, 3.0), Landmark(-20.0, 0.5)},
                             std::pair{Pose(1.0, -1.0, -12.0), Landmark(1.5, -30.0)}}) {
    RowMajor23 jx;
    RowMajor22 jm;
    EvaluateRangeBearing(*f, x, m, &jx, &jm);
    const Mat23 jx_col = jx;
    const Mat2 jm_col = jm;
    ExpectJacobianNear<2, 3>(
        jx_col, [&](const Vec3& xx) { return EvaluateRangeBearing(*f, xx, m); }, x, 1e-6);
    ExpectJacobianNear<2, 2>(
        jm_col, [&](const Vec2& mm) { return EvaluateRangeBearing(*f, x, mm); }, m, 1e-6);
  }
}

TEST(RangeBearingFactor, RefusesALandmarkOnThePose) {
  const std::unique_ptr<ceres::CostFunction> f(
      RangeBearingFactor::Create(Measurement(1.0, 0.0), Mat2::Identity()));
  const Pose x(2.0, 3.0, 0.0);
  const Landmark m(2.0, 3.0);
  const double* params[] = {x.data(), m.data()};
  Vec2 r;
  EXPECT_FALSE(f->Evaluate(params, r.data(), nullptr));
}

}  // namespace
}  // namespace phdslam::reference
