#include "validation/metrics/trajectory_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace phdslam::validation {
namespace {

TEST(ComputePoseErrors, PositionNormAndUnwrappedHeading) {
  const std::vector<Pose> truth = {Pose(0, 0, 0.0), Pose(10, 5, 3.0), Pose(1, 1, 7.0)};
  const std::vector<Pose> estimate = {Pose(3, 4, 0.1), Pose(10, 5, -3.0), Pose(1, 2, 7.0)};
  const PoseErrors e = ComputePoseErrors(truth, estimate);
  ASSERT_EQ(e.position_m.size(), 3u);
  EXPECT_DOUBLE_EQ(e.position_m[0], 5.0);
  EXPECT_DOUBLE_EQ(e.position_m[1], 0.0);
  EXPECT_DOUBLE_EQ(e.position_m[2], 1.0);
  EXPECT_DOUBLE_EQ(e.heading_rad[0], 0.1);
  // 3 - (-3) = 6 rad, not wrapped to 6 - 2 pi.
  EXPECT_DOUBLE_EQ(e.heading_rad[1], 6.0);
  EXPECT_DOUBLE_EQ(e.heading_rad[2], 0.0);
}

TEST(ComputePoseErrors, RejectsMismatchedSizes) {
  EXPECT_THROW(ComputePoseErrors({Pose::Zero()}, {}), std::invalid_argument);
  EXPECT_THROW(ComputePoseErrors({Pose::Zero()}, {Pose(std::nan(""), 0, 0)}),
               std::invalid_argument);
}

TEST(RmseAccumulator, PooledByHand) {
  // Errors 3, 4 (run 1) and 0, 5 (run 2): mean e^2 = (9 + 16 + 0 + 25) / 4 = 12.5; mean e = 3;
  // sample variance = ((0)^2 + 1^2 + 3^2 + 2^2) / 3 = 14 / 3.
  RmseAccumulator pooled;
  pooled.Add(std::vector<double>{3.0, 4.0});
  pooled.Add(std::vector<double>{0.0, 5.0});
  const PooledRmse r = pooled.Result();
  EXPECT_EQ(r.count, 4u);
  EXPECT_NEAR(r.rmse, std::sqrt(12.5), 1e-15);
  EXPECT_NEAR(r.error_std, std::sqrt(14.0 / 3.0), 1e-15);

  // Merging per-run accumulators gives the pooled result.
  RmseAccumulator run1;
  run1.Add(std::vector<double>{3.0, 4.0});
  RmseAccumulator run2;
  run2.Add(std::vector<double>{0.0, 5.0});
  RmseAccumulator merged;
  merged.Merge(run1);
  merged.Merge(run2);
  EXPECT_EQ(merged.Result().count, 4u);
  EXPECT_NEAR(merged.Result().rmse, r.rmse, 1e-15);
  EXPECT_NEAR(merged.Result().error_std, r.error_std, 1e-14);
}

TEST(RmseAccumulator, PoolsErrorsNotPerRunRmses) {
  // Runs {1} and {3, 3, 3}: pooled sqrt((1 + 27) / 4) = sqrt(7), not the mean (1 + 3) / 2 of the
  // per-run RMSEs.
  RmseAccumulator a;
  a.Add(1.0);
  RmseAccumulator b;
  b.Add(std::vector<double>{3.0, 3.0, 3.0});
  a.Merge(b);
  EXPECT_NEAR(a.Result().rmse, std::sqrt(7.0), 1e-15);
  // Errors 1, 3, 3, 3: mean 2.5, sample variance (2.25 + 3 * 0.25) / 3 = 1.
  EXPECT_NEAR(a.Result().error_std, 1.0, 1e-15);
}

TEST(RmseAccumulator, EdgeCasesAndNaNHandling) {
  RmseAccumulator empty;
  EXPECT_EQ(empty.Result().count, 0u);
  EXPECT_TRUE(std::isnan(empty.Result().rmse));
  RmseAccumulator one;
  one.Add(-2.0);
  EXPECT_DOUBLE_EQ(one.Result().rmse, 2.0);
  EXPECT_EQ(one.Result().error_std, 0.0);
  EXPECT_THROW(one.Add(std::nan("")), std::invalid_argument);
  RmseAccumulator gps;
  EXPECT_EQ(gps.AddSkippingNaN({1.0, std::nan(""), 1.0}), 2u);
  EXPECT_DOUBLE_EQ(gps.Result().rmse, 1.0);
  EXPECT_THROW(gps.AddSkippingNaN({std::numeric_limits<double>::infinity()}),
               std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::validation
