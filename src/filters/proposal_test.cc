#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <numbers>

#include "src/filters/gaussian_mixture_proposal.h"

namespace phdslam::filters {
namespace {

TEST(GaussianMixtureProposal, DensityMatchesDirectSumAndPickFollowsCumulativeWeights) {
  GaussianMixtureProposal g;
  g.Add(std::log(2.0), Pose(0, 0, 0), Vec3(1.0, 2.0, 0.1).asDiagonal());
  g.Add(std::log(6.0), Pose(1, -1, 0.2), Vec3(0.5, 0.5, 0.2).asDiagonal());
  g.Add(0.0, Pose(5, 5, 5), Mat3::Zero());  // invalid factor: ignored by the density
  const PreparedProposal p = PrepareProposal(g);
  const Pose x(0.3, -0.4, 0.05);
  double direct = 0.0;
  for (int t = 0; t < 2; ++t) {
    const Vec3 d = x - g.means[t];
    const double w = std::exp(g.log_weights[t]) / 9.0;
    direct += w * std::exp(-0.5 * d.dot(g.covs[t].inverse() * d)) /
              std::sqrt(std::pow(2 * std::numbers::pi, 3) * g.covs[t].determinant());
  }
  EXPECT_NEAR(LogMixtureDensity(p, x), std::log(direct), 1e-12);
  EXPECT_EQ(PickComponent(p, 0.0), 0);
  EXPECT_EQ(PickComponent(p, 2.0 / 9.0 - 1e-9), 0);
  EXPECT_EQ(PickComponent(p, 2.0 / 9.0 + 1e-9), 1);
  EXPECT_EQ(PickComponent(p, 0.95), 2);
  EXPECT_FALSE(p.chol[2].has_value());
}

}  // namespace
}  // namespace phdslam::filters
