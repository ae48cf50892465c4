#include "validation/metrics/nees.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

namespace phdslam::validation {
namespace {

TEST(Nees, IdentityCovarianceGivesSquaredError) {
  const Pose truth(1.0, 2.0, 10.0);
  const Pose estimate(4.0, -2.0, 10.0 - 2.0 * M_PI - 0.5);
  // Heading difference 2 pi + 0.5 is not wrapped.
  const double heading = 2.0 * M_PI + 0.5;
  EXPECT_NEAR(PoseNees(truth, estimate, Mat3::Identity()), 9.0 + 16.0 + heading * heading, 1e-12);
  EXPECT_NEAR(LandmarkNees(Landmark(1, 1), Landmark(2, 3), Mat2::Identity()), 5.0, 1e-15);
}

TEST(Nees, UsesTheInverseCovariance) {
  Mat2 cov;
  cov << 4.0, 1.0, 1.0, 2.0;
  const Vec2 e(1.0, -1.0);
  EXPECT_NEAR(LandmarkNees(e, Landmark::Zero(), cov), e.dot(cov.inverse() * e), 1e-14);
  Mat3 pose_cov = Mat3::Zero();
  pose_cov.diagonal() << 4.0, 9.0, 0.01;
  EXPECT_NEAR(PoseNees(Pose(2, 3, 0.1), Pose::Zero(), pose_cov), 1.0 + 1.0 + 1.0, 1e-12);
}

TEST(Nees, RejectsSingularOrBadCovariance) {
  EXPECT_THROW(PoseNees(Pose::Zero(), Pose::Zero(), Mat3::Zero()), std::invalid_argument);
  Mat2 indefinite;
  indefinite << 1.0, 2.0, 2.0, 1.0;
  EXPECT_THROW(LandmarkNees(Landmark::Zero(), Landmark::Zero(), indefinite), std::invalid_argument);
  Mat2 asymmetric;
  asymmetric << 1.0, 0.5, 0.0, 1.0;
  EXPECT_THROW(LandmarkNees(Landmark::Zero(), Landmark::Zero(), asymmetric), std::invalid_argument);
}

TEST(AveragedNeesBounds, ChiSquareQuantilesOverRuns) {
  // 100 runs of a 3-dimensional state: chi2_300 quantiles / 100.
  const NeesBounds pose = AveragedNeesBounds(3, 100);
  EXPECT_NEAR(pose.lower, 2.539123226024897287, 1e-10);
  EXPECT_NEAR(pose.upper, 3.498744688299152572, 1e-10);
  const NeesBounds landmark = AveragedNeesBounds(2, 100);
  EXPECT_NEAR(landmark.lower, 1.6272798250184628128, 1e-10);
  EXPECT_NEAR(landmark.upper, 2.4105789550631091404, 1e-10);
  const NeesBounds single = AveragedNeesBounds(3, 1, 0.05);
  EXPECT_NEAR(single.lower, 0.21579528262389787679, 1e-11);
  EXPECT_NEAR(single.upper, 9.3484036044961458456, 1e-9);
  const NeesBounds wide = AveragedNeesBounds(20, 1, 0.01);
  EXPECT_NEAR(wide.lower, 7.4338442629342350571, 1e-9);
  EXPECT_NEAR(wide.upper, 39.996846312938643766, 1e-8);
  EXPECT_THROW(AveragedNeesBounds(0, 10), std::invalid_argument);
  EXPECT_THROW(AveragedNeesBounds(2, 0), std::invalid_argument);
  EXPECT_THROW(AveragedNeesBounds(2, 10, 1.0), std::invalid_argument);
}

TEST(SummariseNees, AveragesOverRunsAndCountsStepsInside) {
  // Two runs of a 2-D state: bounds chi2_4(0.025) / 2 = 0.2422 and chi2_4(0.975) / 2 = 5.5716.
  const std::vector<std::vector<double>> nees = {{1.0, 12.0, 0.1, 0.4}, {3.0, 10.0, 0.1, 0.2}};
  const NeesConsistency s = SummariseNees(nees, 2);
  ASSERT_EQ(s.mean_nees.size(), 4u);
  EXPECT_DOUBLE_EQ(s.mean_nees[0], 2.0);
  EXPECT_DOUBLE_EQ(s.mean_nees[1], 11.0);
  EXPECT_DOUBLE_EQ(s.mean_nees[2], 0.1);
  EXPECT_DOUBLE_EQ(s.mean_nees[3], 0.3);
  EXPECT_NEAR(s.bounds.lower, 0.4844185570879298204 / 2.0, 1e-12);
  EXPECT_NEAR(s.bounds.upper, 11.143286781877795099 / 2.0, 1e-10);
  EXPECT_DOUBLE_EQ(s.fraction_inside, 0.5);  // steps 0 and 3
  EXPECT_THROW(SummariseNees({}, 2), std::invalid_argument);
  EXPECT_THROW(SummariseNees({{1.0, 2.0}, {1.0}}, 2), std::invalid_argument);
  EXPECT_THROW(SummariseNees({{}}, 2), std::invalid_argument);
}

TEST(MatchedLandmarkNees, OneValuePerGospaPair) {
  const std::vector<Landmark> truth = {Landmark(0, 0), Landmark(10, 0), Landmark(50, 50)};
  const std::vector<Landmark> estimate = {Landmark(10, 2), Landmark(1, 0)};
  std::vector<Mat2> covs = {Mat2::Identity() * 4.0, Mat2::Identity()};
  const GospaResult g = Gospa(truth, estimate, 20.0, 2.0);
  ASSERT_EQ(g.pairs.size(), 2u);
  const std::vector<double> nees = MatchedLandmarkNees(truth, estimate, covs, g);
  ASSERT_EQ(nees.size(), 2u);
  EXPECT_NEAR(nees[0], 1.0, 1e-14);        // truth 0 with estimate 1: d^2 = 1, unit covariance
  EXPECT_NEAR(nees[1], 4.0 / 4.0, 1e-14);  // truth 1 with estimate 0: d^2 = 4, covariance 4 I
  covs.pop_back();
  EXPECT_THROW(MatchedLandmarkNees(truth, estimate, covs, g), std::invalid_argument);
  GospaResult bad = g;
  bad.pairs.emplace_back(7, 0);
  covs.push_back(Mat2::Identity());
  EXPECT_THROW(MatchedLandmarkNees(truth, estimate, covs, bad), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::validation
