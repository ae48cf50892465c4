#include "reference/ceres/batch_smoother.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <tuple>

#include "reference/ceres/test_scenario.h"
#include "src/core/angles.h"
#include "src/testing/jacobian_check.h"

namespace phdslam::reference {
namespace {

using testing::CircleScenarioOptions;
using testing::MakeCircleScenario;
using testing::PositionRmse;

CircleScenarioOptions NoiseFree() {
  CircleScenarioOptions o;
  o.noise = false;
  o.detection_probability = 1.0;
  return o;
}

void ExpectTruthRecovered(const datasets::Scenario& s, const datasets::BatchResult& r,
                          const std::vector<int>& labels, double tol) {
  ASSERT_EQ(r.poses.size(), s.truth.poses.size());
  for (std::size_t k = 0; k < r.poses.size(); ++k) {
    EXPECT_LT((r.poses[k] - s.truth.poses[k]).norm(), tol) << "step " << k;
  }
  ASSERT_EQ(r.map.means.size(), labels.size());
  for (std::size_t i = 0; i < labels.size(); ++i) {
    EXPECT_LT((r.map.means[i] - s.truth.landmarks[static_cast<std::size_t>(labels[i])]).norm(), tol)
        << "landmark " << i;
  }
}

TEST(BatchSmoother, NoiseFreeKnownAssociationRecoversTheTruth) {
  const datasets::Scenario s = MakeCircleScenario(NoiseFree());
  BatchSmoother smoother(SmootherOptions{});
  const datasets::BatchResult r = smoother.Solve(s);
  ASSERT_EQ(smoother.landmark_labels().size(), 20u);  // every landmark of the ring is seen
  for (std::size_t i = 0; i < 20; ++i) EXPECT_EQ(smoother.landmark_labels()[i], int(i));
  ExpectTruthRecovered(s, r, smoother.landmark_labels(), 1e-6);
  EXPECT_NEAR(smoother.report().final_cost, 0.0, 1e-12);
}

TEST(BatchSmoother, NoiseFreeCarModelWithSubIntervalsAndAnchoredFirstStep) {
  CircleScenarioOptions o = NoiseFree();
  o.motion = datasets::MotionKind::kCar;
  o.sub_intervals = 4;
  o.first_step_propagates = true;
  const datasets::Scenario s = MakeCircleScenario(o);
  BatchSmoother smoother(SmootherOptions{});
  const datasets::BatchResult r = smoother.Solve(s);
  ExpectTruthRecovered(s, r, smoother.landmark_labels(), 1e-6);
  // Pose 0 is estimated (linked to the fixed initial pose by step 0's odometry).
  ASSERT_TRUE(r.pose_covs[0].has_value());
  phdslam::testing::ExpectSymmetricPositiveDefinite(*r.pose_covs[0]);
}

class SmoothingBeatsDeadReckoning : public ::testing::TestWithParam<OdometryResidual> {};

TEST_P(SmoothingBeatsDeadReckoning, WithNoise) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  SmootherOptions o;
  o.odometry_residual = GetParam();
  BatchSmoother smoother(o);
  const datasets::BatchResult r = smoother.Solve(s);
  const double dr = PositionRmse(s, DeadReckoning(s, ScenarioOdometry(s, {})));
  const double sm = PositionRmse(s, r.poses);
  std::cout << "dead reckoning RMSE " << dr << " m, smoother RMSE " << sm << " m, "
            << smoother.report().iterations << " iterations\n";
  EXPECT_LT(sm, 0.5 * dr);
  double map_err = 0.0;
  for (std::size_t i = 0; i < r.map.means.size(); ++i) {
    map_err = std::max(map_err, (r.map.means[i] - s.truth.landmarks[i]).norm());
  }
  EXPECT_LT(map_err, 3.0);
  EXPECT_GT(smoother.report().iterations, 0);
  EXPECT_EQ(r.iterations, smoother.report().iterations);
}

INSTANTIATE_TEST_SUITE_P(BatchSmoother, SmoothingBeatsDeadReckoning,
                         ::testing::Values(OdometryResidual::kControlSpace,
                                           OdometryResidual::kPoseSpace));

TEST(BatchSmoother, CovariancesAreSymmetricPositiveDefiniteAndConsistent) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  BatchSmoother smoother(SmootherOptions{});
  const datasets::BatchResult r = smoother.Solve(s);
  ASSERT_TRUE(smoother.report().covariance_ok);
  ASSERT_EQ(r.pose_covs.size(), r.poses.size());
  ASSERT_TRUE(r.pose_covs[0].has_value());
  EXPECT_EQ(*r.pose_covs[0], Mat3::Zero());  // the initial pose is known exactly
  double nees = 0.0;
  for (std::size_t k = 1; k < r.poses.size(); ++k) {
    ASSERT_TRUE(r.pose_covs[k].has_value());
    phdslam::testing::ExpectSymmetricPositiveDefinite(*r.pose_covs[k]);
    const Vec3 e = r.poses[k] - s.truth.poses[k];
    nees += e.dot(r.pose_covs[k]->ldlt().solve(e));
  }
  nees /= static_cast<double>(r.poses.size() - 1);
  ASSERT_EQ(r.map.covs.size(), r.map.means.size());
  for (const Mat2& p : r.map.covs) phdslam::testing::ExpectSymmetricPositiveDefinite(p);
  // Mean pose NEES of a consistent 3-D estimate is 3. The 99 poses share one realisation of the
  // noise, so the average is loose; a wrong whitening (e.g. sigma instead of sigma^2) is off by
  // orders of magnitude.
  std::cout << "mean pose NEES " << nees << " (covariance " << smoother.report().covariance_seconds
            << " s)\n";
  EXPECT_GT(nees, 0.5);
  EXPECT_LT(nees, 12.0);
}

TEST(BatchSmoother, SchurAndNormalCholeskyAgree) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  SmootherOptions o;
  o.compute_covariances = false;
  const datasets::BatchResult a = BatchSmoother(o).Solve(s);
  o.linear_solver = SparseLinearSolver::kSparseSchur;
  const datasets::BatchResult b = BatchSmoother(o).Solve(s);
  for (std::size_t k = 0; k < a.poses.size(); ++k) {
    EXPECT_LT((a.poses[k] - b.poses[k]).norm(), 1e-4);
  }
  // Without covariances the map carries the pose-known approximation.
  ASSERT_EQ(a.map.covs.size(), a.map.means.size());
  EXPECT_FALSE(a.pose_covs[5].has_value());
}

TEST(BatchSmoother, FilterModeWithRelabelledTruthEqualsKnownMode) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  SmootherOptions known;
  known.compute_covariances = false;
  const datasets::BatchResult a = BatchSmoother(known).Solve(s);
  SmootherOptions filter = known;
  filter.association = AssociationMode::kFilter;
  filter.robust_loss = "none";
  for (const auto& step : s.steps) {
    std::vector<int> labels;
    for (int o : step.origin) labels.push_back(o < 0 ? -1 : 1000 - 7 * o);
    filter.filter_association.push_back(labels);
  }
  BatchSmoother smoother(filter);
  const datasets::BatchResult b = smoother.Solve(s);
  ASSERT_EQ(b.map.means.size(), a.map.means.size());
  const std::size_t n = a.map.means.size();
  for (std::size_t i = 0; i < n; ++i) {
    // Labels are sorted increasingly, so the map comes out in reverse truth order.
    EXPECT_EQ(smoother.landmark_labels()[i], 1000 - 7 * static_cast<int>(n - 1 - i));
    EXPECT_LT((b.map.means[i] - a.map.means[n - 1 - i]).norm(), 1e-6);
  }
  for (std::size_t k = 0; k < a.poses.size(); ++k)
    EXPECT_LT((a.poses[k] - b.poses[k]).norm(), 1e-6);
}

TEST(BatchSmoother, RejectsLabelsThatDoNotMatchTheMeasurements) {
  datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  s.steps[3].origin.pop_back();
  EXPECT_THROW(BatchSmoother(SmootherOptions{}).Solve(s), std::invalid_argument);
  SmootherOptions o;
  o.association = AssociationMode::kFilter;
  o.filter_association.resize(2);
  EXPECT_THROW(BatchSmoother(o).Solve(s), std::invalid_argument);
}

TEST(BatchSmoother, RejectsBadOptions) {
  SmootherOptions o;
  o.robust_loss = "tukey-ish";
  EXPECT_THROW(BatchSmoother{o}, std::invalid_argument);
  o = SmootherOptions{};
  o.min_observations = 0;
  EXPECT_THROW(BatchSmoother{o}, std::invalid_argument);
  o = SmootherOptions{};
  o.max_iterations = 0;
  EXPECT_THROW(BatchSmoother{o}, std::invalid_argument);
}

TEST(BatchSmoother, UnknownAssociationWithoutNoiseRecoversTheTruth) {
  const datasets::Scenario s = MakeCircleScenario(NoiseFree());
  SmootherOptions o;
  o.association = AssociationMode::kUnknown;
  BatchSmoother smoother(o);
  const datasets::BatchResult r = smoother.Solve(s);
  ASSERT_EQ(r.map.means.size(), 20u);
  // Map index -> truth index through the association (consistent for every measurement).
  std::vector<int> truth_of(20, -1);
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    for (std::size_t j = 0; j < s.steps[k].origin.size(); ++j) {
      const int i = smoother.association()[k][j];
      ASSERT_GE(i, 0);
      if (truth_of[static_cast<std::size_t>(i)] < 0) {
        truth_of[static_cast<std::size_t>(i)] = s.steps[k].origin[j];
      }
      EXPECT_EQ(truth_of[static_cast<std::size_t>(i)], s.steps[k].origin[j]);
    }
  }
  ExpectTruthRecovered(s, r, truth_of, 1e-6);
  EXPECT_TRUE(smoother.report().association_converged);
}

// (initialisation, incremental_squared_marginals)
class UnknownAssociationWithClutter
    : public ::testing::TestWithParam<std::tuple<SmootherInitialisation, bool>> {};

TEST_P(UnknownAssociationWithClutter, RecoversTheLandmarkCount) {
  CircleScenarioOptions c;
  c.clutter_rate = 5.0;
  c.seed = 7;
  const datasets::Scenario s = MakeCircleScenario(c);
  SmootherOptions o;
  o.association = AssociationMode::kUnknown;
  o.initialisation = std::get<0>(GetParam());
  o.incremental_squared_marginals = std::get<1>(GetParam());
  o.initial_pass_solve_steps = 25;  // exercise the intermediate solves on this short run
  o.incremental_chunk_steps = 25;
  BatchSmoother smoother(o);
  const datasets::BatchResult r = smoother.Solve(s);
  // 100 steps: the batch pass solves after steps 25, 50 and 75; the incremental one after every
  // chunk of 25, the last included.
  const int pass_solves = std::get<0>(GetParam()) == SmootherInitialisation::kBatch ? 3 : 4;
  EXPECT_EQ(smoother.report().solves, pass_solves + smoother.report().reassociation_rounds + 1);
  // Association accuracy against the hidden labels.
  int true_pos = 0;
  int detections = 0;
  int clutter_kept = 0;
  std::vector<std::vector<int>> votes(r.map.means.size(), std::vector<int>(20, 0));
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    for (std::size_t j = 0; j < s.steps[k].origin.size(); ++j) {
      const int i = smoother.association()[k][j];
      const int t = s.steps[k].origin[j];
      if (t >= 0) ++detections;
      if (i >= 0 && t >= 0) ++votes[static_cast<std::size_t>(i)][static_cast<std::size_t>(t)];
      if (i >= 0 && t < 0) ++clutter_kept;
    }
  }
  for (const auto& v : votes) true_pos += *std::max_element(v.begin(), v.end());
  std::cout << "landmarks " << r.map.means.size() << ", detections associated to their majority "
            << "landmark " << true_pos << "/" << detections << ", clutter kept " << clutter_kept
            << ", rounds " << smoother.report().reassociation_rounds << ", RMSE "
            << PositionRmse(s, r.poses) << " m\n";
  // Stated band: all 20 landmarks found, at most one spurious one from clutter.
  EXPECT_GE(r.map.means.size(), 20u);
  EXPECT_LE(r.map.means.size(), 21u);
  EXPECT_GT(true_pos, 0.98 * detections);
  EXPECT_LT(clutter_kept, 10);
  const double dr = PositionRmse(s, DeadReckoning(s, ScenarioOdometry(s, {})));
  EXPECT_LT(PositionRmse(s, r.poses), 0.5 * dr);
}

INSTANTIATE_TEST_SUITE_P(
    BatchSmoother, UnknownAssociationWithClutter,
    ::testing::Values(std::make_tuple(SmootherInitialisation::kIncremental, false),
                      std::make_tuple(SmootherInitialisation::kIncremental, true),
                      std::make_tuple(SmootherInitialisation::kBatch, false)));

// The incremental solve ends where the batch solve from dead reckoning ends: the same graph, the
// same minimum, whatever the linearisation points on the way.
TEST(BatchSmoother, IncrementalSolveReachesTheBatchSolution) {
  CircleScenarioOptions c;
  c.steps = 120;
  const datasets::Scenario s = MakeCircleScenario(c);
  SmootherOptions o;
  o.function_tolerance = 1e-14;
  o.compute_covariances = false;
  o.initialisation = SmootherInitialisation::kBatch;
  BatchSmoother batch(o);
  const datasets::BatchResult b = batch.Solve(s);
  o.initialisation = SmootherInitialisation::kIncremental;
  o.incremental_chunk_steps = 10;
  o.incremental_active_steps = 30;  // older poses held during the chunk solves
  BatchSmoother incremental(o);
  const datasets::BatchResult i = incremental.Solve(s);
  EXPECT_GT(incremental.report().solves, batch.report().solves + 10);  // 12 chunk solves
  EXPECT_TRUE(incremental.report().converged);
  ASSERT_EQ(i.poses.size(), b.poses.size());
  for (std::size_t k = 0; k < b.poses.size(); ++k) {
    EXPECT_LT((i.poses[k] - b.poses[k]).norm(), 1e-4) << "step " << k;
  }
  ASSERT_EQ(i.map.means.size(), b.map.means.size());
  for (std::size_t m = 0; m < b.map.means.size(); ++m) {
    EXPECT_LT((i.map.means[m] - b.map.means[m]).norm(), 1e-4) << "landmark " << m;
  }
  EXPECT_LT(PositionRmse(s, i.poses),
            0.5 * PositionRmse(s, DeadReckoning(s, ScenarioOdometry(s, {}))));
}

// A solve stopped by the iteration limit is reported as not converged.
TEST(BatchSmoother, NonConvergenceIsReported) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  SmootherOptions o;
  o.compute_covariances = false;
  BatchSmoother converging(o);
  const datasets::BatchResult ok = converging.Solve(s);
  ASSERT_TRUE(ok.converged);
  EXPECT_TRUE(*ok.converged);
  EXPECT_EQ(converging.report().unconverged_solves, 0);
  o.initialisation = SmootherInitialisation::kBatch;
  o.warm_start_floor = o.odometry_floor;  // no warm start: one solve from dead reckoning
  o.max_iterations = 1;
  BatchSmoother stopped(o);
  const datasets::BatchResult r = stopped.Solve(s);
  ASSERT_TRUE(r.converged);
  EXPECT_FALSE(*r.converged);
  EXPECT_FALSE(stopped.report().converged);
  EXPECT_EQ(stopped.report().unconverged_solves, 1);
}

}  // namespace
}  // namespace phdslam::reference
