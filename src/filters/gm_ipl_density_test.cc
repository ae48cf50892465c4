// Focused tests of PHD-SLAM 3.0's importance density (docs/algorithms/phd-slam.md section 4.3-4.6):
// the mixture over the Murty-ranked associations, each component conditioned by the partitioned
// IPL, plus the all-clutter component.
#include "src/filters/gm_ipl_density.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/filters/ipl.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {
namespace {

models::SensorModel Sensor() {
  models::SensorModel s;
  s.noise_cov << 0.64, 0.0, 0.0, 2.7416e-5;
  return s;
}

const Pose kTruth(300.0, 400.0, -0.1);
const Pose kPriorMean(300.6, 399.6, -0.096);

Mat3 PriorCov() {
  Mat3 sigma0;
  sigma0 << 0.7, 0.1, 0.001, 0.1, 0.5, 0.002, 0.001, 0.002, 1e-4;
  return sigma0;
}

std::vector<phd::GaussianComponent> Landmarks(const std::vector<Landmark>& means) {
  std::vector<phd::GaussianComponent> out;
  for (const Landmark& m : means) out.push_back({m, Mat2::Identity() * 0.2, std::log(0.9)});
  return out;
}

TEST(GmIplDensity, AnEmptyMapGivesThePriorAndNoAssociation) {
  const models::SensorModel sensor = Sensor();
  const std::vector<Measurement> z = {Measurement(40.0, 0.2), Measurement(70.0, -0.4)};
  const ProposalOutput out =
      GmIplDensity(PhdSlamParams{}).Build({kPriorMean, PriorCov(), {}, z, &sensor, {}});
  ASSERT_EQ(out.mixture.size(), 1u);
  EXPECT_EQ(out.mixture.means[0], kPriorMean);
  EXPECT_EQ(out.mixture.covs[0], PriorCov());
  EXPECT_EQ(out.best_association, (std::vector<int>{-1, -1}));
}

TEST(GmIplDensity, OneDetectionIsTheIplPosteriorWeightedByEquation44) {
  const models::SensorModel sensor = Sensor();
  const std::vector<phd::GaussianComponent> map = Landmarks({Landmark(340.0, 410.0)});
  const std::vector<Measurement> z = {models::PredictMeasurement(kTruth, map[0].mean)};
  const PhdSlamParams params;
  const ProposalOutput out =
      GmIplDensity(params).Build({kPriorMean, PriorCov(), map, z, &sensor, {}});
  // The detection hypothesis, then the all-clutter component (the prior).
  ASSERT_EQ(out.mixture.size(), 2u);
  EXPECT_EQ(out.best_association, (std::vector<int>{0}));
  const std::vector<IplPair> pairs = {{map[0].mean, map[0].cov, z[0]}};
  const IplResult ipl = PartitionedIpl(kPriorMean, PriorCov(), pairs, sensor.noise_cov,
                                       {params.ipl_iterations, params.ipl_kl_tolerance});
  EXPECT_EQ(out.mixture.means[0], ipl.mean);
  EXPECT_EQ(out.mixture.covs[0], ipl.cov);
  EXPECT_LT((ipl.mean - kTruth).head<2>().norm(), (kPriorMean - kTruth).head<2>().norm());
  EXPECT_EQ(out.mixture.means[1], kPriorMean);
  EXPECT_EQ(out.mixture.covs[1], PriorCov());
  // Equation (44): kappa_det = pD w N(z; h(m, x_ipl), S) / lambda_c with
  // S = Hx P_ipl Hx^T + Hm P_m Hm^T + R, and the all-clutter weight is the missed mass
  // (1 - pD) w, so the landmark's weight w cancels in the ratio.
  const double pd = sensor.DetectionProbability(kPriorMean, map[0].mean);
  const auto jac = models::MeasurementJacobians(ipl.mean, map[0].mean);
  const Mat2 s = jac.hx * ipl.cov * jac.hx.transpose() + jac.hm * map[0].cov * jac.hm.transpose() +
                 sensor.noise_cov;
  Vec2 nu = z[0] - models::PredictMeasurement(ipl.mean, map[0].mean);
  nu(1) = WrapAngle(nu(1));
  const double expected = std::log(pd) + *LogNormalPdf<2>(nu, Vec2::Zero(), s) -
                          std::log(sensor.ClutterIntensity()) - std::log1p(-pd);
  EXPECT_NEAR(out.mixture.log_weights[0] - out.mixture.log_weights[1], expected, 1e-9);
}

TEST(GmIplDensity, TheAllClutterComponentIsAnOption) {
  const models::SensorModel sensor = Sensor();
  const std::vector<phd::GaussianComponent> map = Landmarks({Landmark(340.0, 410.0)});
  const std::vector<Measurement> z = {models::PredictMeasurement(kTruth, map[0].mean)};
  PhdSlamParams params;
  params.all_clutter_component = false;
  const ProposalOutput out =
      GmIplDensity(params).Build({kPriorMean, PriorCov(), map, z, &sensor, {}});
  ASSERT_GE(out.mixture.size(), 1u);
  for (std::size_t t = 0; t < out.mixture.size(); ++t) EXPECT_NE(out.mixture.covs[t], PriorCov());
}

TEST(GmIplDensity, HypothesesAreCappedAndRankedBestFirst) {
  const models::SensorModel sensor = Sensor();
  const std::vector<phd::GaussianComponent> map =
      Landmarks({Landmark(340.0, 410.0), Landmark(342.0, 411.0), Landmark(320.0, 350.0),
                 Landmark(321.0, 352.0)});
  const std::vector<Measurement> z = {models::PredictMeasurement(kTruth, map[0].mean),
                                      models::PredictMeasurement(kTruth, map[2].mean),
                                      Measurement(60.0, 0.9)};
  for (int cap : {1, 3, 8}) {
    PhdSlamParams params;
    params.max_hypotheses = cap;
    const ProposalOutput out =
        GmIplDensity(params).Build({kPriorMean, PriorCov(), map, z, &sensor, {}});
    EXPECT_LE(out.mixture.size(), static_cast<std::size_t>(cap) + 1) << "cap " << cap;
    EXPECT_GE(out.mixture.size(), 2u) << "cap " << cap;
    // The best hypothesis associates the two landmark measurements with their own landmarks and
    // leaves the far point as clutter.
    EXPECT_EQ(out.best_association, (std::vector<int>{0, 2, -1})) << "cap " << cap;
    for (std::size_t t = 0; t < out.mixture.size(); ++t) {
      EXPECT_TRUE(CholeskyLower<3>(out.mixture.covs[t]).has_value()) << "component " << t;
    }
  }
}

TEST(GmIplDensity, AMeasurementOutsideEveryGateIsNotAssociated) {
  const models::SensorModel sensor = Sensor();
  const std::vector<phd::GaussianComponent> map = Landmarks({Landmark(340.0, 410.0)});
  const std::vector<Measurement> z = {Measurement(41.0, 1.2)};  // 1.2 rad away from the landmark
  const ProposalOutput out =
      GmIplDensity(PhdSlamParams{}).Build({kPriorMean, PriorCov(), map, z, &sensor, {}});
  EXPECT_EQ(out.best_association, (std::vector<int>{-1}));
  for (std::size_t t = 0; t < out.mixture.size(); ++t) {
    EXPECT_EQ(out.mixture.means[t], kPriorMean) << "component " << t;
  }
}

TEST(GmIplDensity, ZeroHypothesesIsTheTransitionDensity) {
  const models::SensorModel sensor = Sensor();
  const std::vector<phd::GaussianComponent> map = Landmarks({Landmark(340.0, 410.0)});
  const std::vector<Measurement> z = {models::PredictMeasurement(kTruth, map[0].mean)};
  PhdSlamParams params;
  params.max_hypotheses = 0;
  const ProposalOutput out =
      GmIplDensity(params).Build({kPriorMean, PriorCov(), map, z, &sensor, {}});
  ASSERT_EQ(out.mixture.size(), 1u);
  EXPECT_EQ(out.mixture.means[0], kPriorMean);
  EXPECT_EQ(out.mixture.covs[0], PriorCov());
}

}  // namespace
}  // namespace phdslam::filters
