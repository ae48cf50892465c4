#include "src/filters/rb_phd_weighting.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <vector>

#include "src/core/angles.h"
#include "src/models/range_bearing_model.h"
#include "src/phd/gm_phd_map.h"

namespace phdslam::filters {
namespace {

double Pdf(const Vec2& x, const Vec2& mu, const Mat2& s) {
  const Vec2 d = x - mu;
  return std::exp(-0.5 * d.dot(s.inverse() * d)) /
         (2.0 * std::numbers::pi * std::sqrt(s.determinant()));
}

double MeasurementPdf(const Measurement& z, const Pose& x, const Landmark& m, const Mat2& r) {
  const double dx = m(0) - x(0);
  const double dy = m(1) - x(1);
  Vec2 nu = z - Vec2(std::hypot(dx, dy), std::atan2(dy, dx) - x(2));
  nu(1) = WrapAngle(nu(1));
  return Pdf(nu, Vec2::Zero(), r);
}

// One landmark a = (w, mu, P) seen from x; z0 near it, z1 far from it (clutter).
struct OneLandmark {
  models::SensorModel sensor;
  Pose x{1.0, 2.0, 0.3};
  phd::GaussianComponent a{Landmark(20.0, 8.0), Mat2::Identity() * 0.5, std::log(0.9)};
  std::vector<Measurement> zs;
  std::vector<phd::GaussianComponent> predicted;
  phd::GmPhdMap map;

  OneLandmark() {
    sensor.noise_cov << 0.64, 0.0, 0.0, 2.7416e-5;
    zs = {models::PredictMeasurement(x, Landmark(20.3, 8.4)), Measurement(100.0, -1.0)};
    predicted = {a};
    map.SetActive(predicted);
    map.Update(x, zs, sensor, phd::MapParams{});
  }
  [[nodiscard]] PhdIntensityPair Pair() const { return {predicted, map.active(), {}}; }
};

// Hand computation of the update: H, S, K of the one landmark at x.
struct HandUpdate {
  double q0;  // weight of the detected copy of z0
  Landmark mean;
  Mat2 cov;
};
HandUpdate Hand(const OneLandmark& e) {
  const double dx = e.a.mean(0) - e.x(0);
  const double dy = e.a.mean(1) - e.x(1);
  const double q = dx * dx + dy * dy;
  Mat2 h;
  h << dx / std::sqrt(q), dy / std::sqrt(q), -dy / q, dx / q;
  const Mat2 s = h * e.a.cov * h.transpose() + e.sensor.noise_cov;
  Vec2 nu = e.zs[0] - Vec2(std::sqrt(q), std::atan2(dy, dx) - e.x(2));
  nu(1) = WrapAngle(nu(1));
  const double gain = 0.95 * 0.9 * Pdf(nu, Vec2::Zero(), s);
  const Mat2 k = e.a.cov * h.transpose() * s.inverse();
  return {gain / (e.sensor.ClutterIntensity() + gain), e.a.mean + k * nu,
          (Mat2::Identity() - k * h) * e.a.cov};
}

TEST(RbPhdWeighting, EmptyMapMatchesHandComputation) {
  const OneLandmark e;
  const HandUpdate u = Hand(e);
  const double kappa = e.sensor.ClutterIntensity();
  // kappa^Z exp(m_k - m_{k|k-1} - lambda), m_k = (1 - pD) w + q0.
  const double expected = 2.0 * std::log(kappa) + (0.05 * 0.9 + u.q0) - 0.9 - 5.0;
  EXPECT_NEAR(EmptyMapLogWeight(e.Pair(), e.zs, e.sensor), expected, 1e-9);
}

TEST(RbPhdWeighting, SingleFeatureMatchesHandComputation) {
  const OneLandmark e;
  const HandUpdate u = Hand(e);
  ASSERT_GT(u.q0, 0.05 * 0.9);  // the detected copy is the evaluation point m*
  const double kappa = e.sensor.ClutterIntensity();
  const Landmark m = u.mean;
  const Mat2& r = e.sensor.noise_cov;
  const double detection =
      0.05 +
      0.95 * (MeasurementPdf(e.zs[0], e.x, m, r) + MeasurementPdf(e.zs[1], e.x, m, r)) / kappa;
  const double v_pred = 0.9 * Pdf(m, e.a.mean, e.a.cov);
  const double v_upd = 0.05 * 0.9 * Pdf(m, e.a.mean, e.a.cov) + u.q0 * Pdf(m, u.mean, u.cov);
  const double expected = 2.0 * std::log(kappa) + std::log(detection) + std::log(v_pred) -
                          std::log(v_upd) + (0.05 * 0.9 + u.q0) - 0.9 - 5.0;
  EXPECT_NEAR(SingleFeatureLogWeight(e.Pair(), e.x, e.zs, e.sensor), expected, 1e-9);
}

TEST(RbPhdWeighting, SingleFeatureWithoutDetectableComponentIsTheEmptyMap) {
  OneLandmark e;
  const Pose behind(e.x(0), e.x(1), e.x(2) + std::numbers::pi);  // the landmark is behind
  EXPECT_DOUBLE_EQ(SingleFeatureLogWeight(e.Pair(), behind, e.zs, e.sensor),
                   EmptyMapLogWeight(e.Pair(), e.zs, e.sensor));
}

TEST(RbPhdWeighting, PassiveComponentsEnterBothIntensities) {
  OneLandmark e;
  const HandUpdate u = Hand(e);
  const std::vector<phd::GaussianComponent> passive = {
      {u.mean + Landmark(1.0, 0.0), Mat2::Identity(), std::log(0.7)}};
  const PhdIntensityPair with{e.predicted, e.map.active(), passive};
  const double p = 0.7 * Pdf(u.mean, u.mean + Landmark(1.0, 0.0), Mat2::Identity());
  const double v_pred = 0.9 * Pdf(u.mean, e.a.mean, e.a.cov);
  const double v_upd =
      0.05 * 0.9 * Pdf(u.mean, e.a.mean, e.a.cov) + u.q0 * Pdf(u.mean, u.mean, u.cov);
  const double shift = std::log((v_pred + p) / (v_upd + p)) - std::log(v_pred / v_upd);
  EXPECT_NEAR(SingleFeatureLogWeight(with, e.x, e.zs, e.sensor) -
                  SingleFeatureLogWeight(e.Pair(), e.x, e.zs, e.sensor),
              shift, 1e-9);
}

TEST(RbPhdWeighting, Paper46PassesTheUpdateLikelihoodThrough) {
  const OneLandmark e;
  EXPECT_EQ(RbPhdLogWeight(RbPhdWeighting::kPaper46, -12.5, e.Pair(), e.x, e.zs, e.sensor), -12.5);
  EXPECT_DOUBLE_EQ(
      RbPhdLogWeight(RbPhdWeighting::kSingleFeature, -12.5, e.Pair(), e.x, e.zs, e.sensor),
      SingleFeatureLogWeight(e.Pair(), e.x, e.zs, e.sensor));
}

}  // namespace
}  // namespace phdslam::filters
