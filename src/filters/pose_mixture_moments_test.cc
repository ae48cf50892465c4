#include "src/filters/pose_mixture_moments.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace phdslam::filters {
namespace {

TEST(PoseMixtureMoments, TwoComponentsMatchAHandComputation) {
  // Weights 1/4 and 3/4; means (0,0,0) and (4,-2,0.4); diagonal covariances.
  const std::vector<PoseMoments> c = {
      {std::log(1.0), Pose(0, 0, 0), Vec3(1.0, 2.0, 0.1).asDiagonal()},
      {std::log(3.0), Pose(4, -2, 0.4), Vec3(0.5, 0.5, 0.2).asDiagonal()}};
  const auto m = MatchMoments(c);
  ASSERT_TRUE(m.has_value());
  // Mean: 0.25 * mu1 + 0.75 * mu2 = (3, -1.5, 0.3).
  EXPECT_NEAR(m->mean(0), 3.0, 1e-12);
  EXPECT_NEAR(m->mean(1), -1.5, 1e-12);
  EXPECT_NEAR(m->mean(2), 0.3, 1e-12);
  EXPECT_NEAR(m->log_weight, std::log(4.0), 1e-12);
  // Spread: w1 w2 (mu2 - mu1)(mu2 - mu1)^T = (3/16) d d^T, d = (4, -2, 0.4).
  const Vec3 d(4.0, -2.0, 0.4);
  Mat3 expected =
      Vec3(0.25 * 1.0 + 0.75 * 0.5, 0.25 * 2.0 + 0.75 * 0.5, 0.25 * 0.1 + 0.75 * 0.2).asDiagonal();
  expected += (3.0 / 16.0) * d * d.transpose();
  EXPECT_TRUE(m->cov.isApprox(expected, 1e-12)) << m->cov;
}

TEST(PoseMixtureMoments, HeadingDifferencesAreWrapped) {
  // Headings pi - 0.1 and -pi + 0.1 are 0.2 apart across the branch cut.
  const double pi = std::numbers::pi;
  const Mat3 p = Mat3::Identity() * 0.01;
  const std::vector<PoseMoments> c = {{0.0, Pose(0, 0, pi - 0.1), p},
                                      {0.0, Pose(0, 0, -pi + 0.1), p}};
  const auto m = MatchMoments(c);
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->mean(2), pi, 1e-12);                  // the first component's branch
  EXPECT_NEAR(m->cov(2, 2), 0.01 + 0.1 * 0.1, 1e-12);  // not (pi - 0.1)^2
}

TEST(PoseMixtureMoments, NoComponentsOrZeroWeightsGiveNothing) {
  EXPECT_FALSE(MatchMoments({}).has_value());
  const std::vector<PoseMoments> c = {
      {-std::numeric_limits<double>::infinity(), Pose::Zero(), Mat3::Identity()}};
  EXPECT_FALSE(MatchMoments(c).has_value());
}

TEST(PoseMixtureMoments, ProposalMomentsUseNormalisedWeightsAndTheFallbackPoint) {
  GaussianMixtureProposal g;
  g.Add(std::log(2.0), Pose(1, 0, 0), Vec3(1.0, 1.0, 0.1).asDiagonal());
  g.Add(std::log(2.0), Pose(9, 9, 9), Mat3::Zero());  // no factor: sampled as the fallback
  const PreparedProposal p = PrepareProposal(g);
  const Pose fallback(3, 0, 0);
  const PoseMoments m = ProposalMoments(p, fallback);
  // Equal weights on N((1,0,0), diag(1,1,0.1)) and the point (3,0,0).
  EXPECT_NEAR(m.mean(0), 2.0, 1e-12);
  EXPECT_NEAR(m.mean(1), 0.0, 1e-12);
  Mat3 expected = Vec3(0.5, 0.5, 0.05).asDiagonal();
  expected(0, 0) += 1.0;  // 0.5 * 1^2 + 0.5 * 1^2
  EXPECT_TRUE(m.cov.isApprox(expected, 1e-12)) << m.cov;
  // A single component is returned unchanged.
  GaussianMixtureProposal one;
  one.Add(0.0, Pose(1, 2, 3), Vec3(0.3, 0.2, 0.1).asDiagonal());
  const PoseMoments single = ProposalMoments(PrepareProposal(one), fallback);
  EXPECT_EQ(single.mean, Pose(1, 2, 3));
  EXPECT_EQ(single.cov, one.covs[0]);
}

}  // namespace
}  // namespace phdslam::filters
