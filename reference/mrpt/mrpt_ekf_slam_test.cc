#include "reference/mrpt/mrpt_ekf_slam.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "reference/mrpt/association_options.h"
#include "reference/mrpt/test_scenarios.h"
#include "src/core/angles.h"
#include "src/filters/odometry_estimator.h"
#include "src/models/velocity_motion_model.h"

namespace phdslam::reference {
namespace {

using testing::CircleScenarioOptions;
using testing::CountCoveredTruth;
using testing::CountFarFromTruth;
using testing::MakeCircleScenario;
using testing::PositionRmse;
using testing::RunOnline;

double DeadReckoningRmse(const datasets::Scenario& s) {
  filters::OdometryEstimator dr(s.PublicContext());
  return PositionRmse(s, RunOnline(dr, s));
}

// 20 landmarks, no clutter, pD = 1, 150 steps: the EKF error stays at the decimetre level
// (observed 0.05-0.13 m) while dead reckoning drifts by metres (observed 2.1-3.6 m).
TEST(MrptEkfSlam, TracksTheTruthWithoutClutter) {
  for (std::uint64_t seed : {1, 2}) {
    const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{}, seed);
    MrptEkfSlam ekf(s.PublicContext());
    const double rmse = PositionRmse(s, RunOnline(ekf, s));
    const double dr = DeadReckoningRmse(s);
    ::testing::Test::RecordProperty("rmse_seed" + std::to_string(seed), std::to_string(rmse));
    ::testing::Test::RecordProperty("dr_rmse_seed" + std::to_string(seed), std::to_string(dr));
    EXPECT_LT(rmse, 0.3) << "seed " << seed;
    EXPECT_LT(rmse, 0.2 * dr) << "seed " << seed;
    const filters::MapEstimate map = ekf.PostProcessedMap();
    EXPECT_EQ(CountCoveredTruth(map, s, 0.5), 20) << "seed " << seed;
    EXPECT_EQ(CountFarFromTruth(map, s, 0.5), 0) << "seed " << seed;
  }
}

// The heading is reported unwrapped: the robot turns 0.1 rad/s for 150 s (more than two turns).
TEST(MrptEkfSlam, ReportsAnUnwrappedHeading) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{}, 3);
  MrptEkfSlam ekf(s.PublicContext());
  const std::vector<Pose> poses = RunOnline(ekf, s);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    ASSERT_NEAR(poses[k](2), s.truth.poses[k](2), 0.05) << "step " << k;
  }
  EXPECT_GT(poses.back()(2), 4.0 * std::numbers::pi);
}

// With clutter, stock MRPT turns (almost) every clutter point into a landmark for good; the
// post-processed map (landmarks associated at least 3 times) keeps exactly the true ones.
TEST(MrptEkfSlam, PostProcessedMapDropsClutterLandmarks) {
  CircleScenarioOptions o;
  o.steps = 100;
  o.clutter_rate = 2.0;
  o.detection_probability = 0.95;
  const datasets::Scenario s = MakeCircleScenario(o, 4);
  MrptEkfSlam ekf(s.PublicContext());
  const double rmse = PositionRmse(s, RunOnline(ekf, s));
  EXPECT_LT(rmse, 0.3);
  EXPECT_LT(rmse, DeadReckoningRmse(s));
  const filters::MapEstimate raw = ekf.Map();
  EXPECT_GT(CountFarFromTruth(raw, s, 1.0), 100);  // about 190 clutter points were generated
  ASSERT_EQ(ekf.AssociationCounts().size(), raw.size());
  const filters::MapEstimate post = ekf.PostProcessedMap();
  EXPECT_EQ(CountFarFromTruth(post, s, 1.0), 0);
  EXPECT_EQ(CountCoveredTruth(post, s, 1.0), 20);
  EXPECT_LT(post.size(), 24U);
}

// The optional track deletion keeps the state small without hurting the estimate.
TEST(MrptEkfSlam, TrackDeletionRemovesClutterFromTheState) {
  CircleScenarioOptions o;
  o.steps = 100;
  o.clutter_rate = 2.0;
  o.detection_probability = 0.95;
  const datasets::Scenario s = MakeCircleScenario(o, 4);
  MrptEkfSlamOptions eo;
  eo.prune_after_steps = 5;
  MrptEkfSlam ekf(s.PublicContext(), eo);
  EXPECT_LT(PositionRmse(s, RunOnline(ekf, s)), 0.3);
  const filters::MapEstimate raw = ekf.Map();
  // At most the clutter of the last five scans (about 10 points) is still tentative.
  EXPECT_LT(CountFarFromTruth(raw, s, 1.0), 25);
  EXPECT_EQ(CountCoveredTruth(raw, s, 1.0), 20);
  EXPECT_EQ(CountFarFromTruth(ekf.PostProcessedMap(), s, 1.0), 0);
}

// MRPT's EKF update P <- (I - K H) P does not keep P symmetric; the default re-symmetrises it.
TEST(MrptEkfSlam, KeepsThePoseCovarianceSymmetric) {
  CircleScenarioOptions o;
  o.steps = 60;
  const datasets::Scenario s = MakeCircleScenario(o, 2);
  MrptEkfSlamOptions stock;
  stock.symmetrize_covariance = false;
  MrptEkfSlam a(s.PublicContext());
  MrptEkfSlam b(s.PublicContext(), stock);
  double worst_stock = 0.0;
  for (const datasets::ScenarioStep& step : s.steps) {
    const filters::StepOutput oa = a.Step(step.data);
    const filters::StepOutput ob = b.Step(step.data);
    ASSERT_EQ(*oa.pose_cov, oa.pose_cov->transpose());
    worst_stock =
        std::max(worst_stock, (*ob.pose_cov - ob.pose_cov->transpose()).cwiseAbs().maxCoeff());
  }
  EXPECT_GT(worst_stock, 0.0);
}

filters::EstimatorContext StaticContext() {
  filters::EstimatorContext c;
  c.initial_pose = Pose::Zero();
  c.motion = std::make_shared<models::VelocityMotionModel>();
  c.control_noise_cov = Mat2::Identity() * 1e-4;
  c.sensor.fov_range = 150.0;
  c.sensor.noise_cov = Vec2(0.3 * 0.3, DegToRad(0.5) * DegToRad(0.5)).asDiagonal();
  return c;
}

// Landmark A at (10 m, 0 rad) and B at (10.3 m, 0.2 rad); then A is measured 0.3 m (one sigma)
// long, at (10.3, 0). In (m, rad) units the prediction of B is nearer (0.2) than that of A (0.3),
// and B's squared Mahalanobis distance (about 260) exceeds 6 chi2inv(0.999, 2) = 83, so stock
// MRPT's KD-tree search stops before testing A and creates a duplicate; with the full search A is
// associated (squared distance 0.5).
TEST(MrptEkfSlam, FullCandidateSearchFindsTheLandmarkTheKdTreeHides) {
  datasets::StepData first;
  first.times = {0.0};
  first.measurements = {Measurement(10.0, 0.0), Measurement(10.3, 0.2)};
  datasets::StepData second;
  second.times = {1.0};
  second.measurements = {Measurement(10.3, 0.0)};
  for (bool kdtree : {false, true}) {
    MrptEkfSlamOptions o;
    o.mrpt_kdtree_candidates = kdtree;
    MrptEkfSlam ekf(StaticContext(), o);
    ekf.Step(first);
    ekf.Step(second);
    if (kdtree) {
      EXPECT_EQ(ekf.Map().size(), 3U);
      EXPECT_EQ(ekf.LastAssociations(), std::vector<int>({-1}));
    } else {
      EXPECT_EQ(ekf.Map().size(), 2U);
      EXPECT_EQ(ekf.LastAssociations(), std::vector<int>({0}));
      EXPECT_EQ(ekf.AssociationCounts(), std::vector<int>({1, 0}));
    }
  }
}

// While the map is empty MRPT skips its prediction; the wrapper applies the odometry itself, so
// the pose follows the motion model: 3 steps at v = 1, omega = 0 from the origin.
TEST(MrptEkfSlam, MovesWhileTheMapIsEmpty) {
  MrptEkfSlam ekf(StaticContext());
  datasets::StepData step;
  step.times = {0.0};
  ekf.Step(step);
  for (int k = 1; k <= 3; ++k) {
    step.times = {k - 1.0, static_cast<double>(k)};
    step.controls = {Control(1.0, 0.0)};
    const filters::StepOutput out = ekf.Step(step);
    EXPECT_NEAR(out.pose(0), k, 1e-9);
    EXPECT_NEAR(out.pose(1), 0.0, 1e-9);
    ASSERT_TRUE(out.pose_cov.has_value());
    // The along-track variance grows by dt^2 q_v = 1e-4 per step.
    EXPECT_NEAR((*out.pose_cov)(0, 0), k * 1e-4, 1e-12);
  }
}

TEST(MrptEkfSlam, SameInputGivesIdenticalResults) {
  CircleScenarioOptions o;
  o.steps = 60;
  o.clutter_rate = 2.0;
  const datasets::Scenario s = MakeCircleScenario(o, 5);
  MrptEkfSlam a(s.PublicContext());
  MrptEkfSlam b(s.PublicContext());
  for (const datasets::ScenarioStep& step : s.steps) {
    const filters::StepOutput oa = a.Step(step.data);
    const filters::StepOutput ob = b.Step(step.data);
    ASSERT_EQ(oa.pose, ob.pose);
  }
  EXPECT_EQ(a.Map().means, b.Map().means);
}

// MRPT's EKF writes no file into the working directory.
TEST(MrptEkfSlam, WritesNoFiles) {
  const std::filesystem::path before = std::filesystem::current_path();
  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() / "phdslam_mrpt_ekf_scratch_test";
  std::filesystem::remove_all(scratch);
  std::filesystem::create_directories(scratch);
  std::filesystem::current_path(scratch);
  {
    CircleScenarioOptions o;
    o.steps = 20;
    o.clutter_rate = 2.0;
    const datasets::Scenario s = MakeCircleScenario(o, 6);
    MrptEkfSlam ekf(s.PublicContext());
    RunOnline(ekf, s);
  }
  std::filesystem::current_path(before);
  EXPECT_TRUE(std::filesystem::is_empty(scratch));
  std::filesystem::remove_all(scratch);
}

TEST(MrptEkfSlam, RejectsBadConfiguration) {
  filters::EstimatorContext c = StaticContext();
  c.sensor.noise_cov(0, 1) = c.sensor.noise_cov(1, 0) = 1e-4;
  EXPECT_THROW(MrptEkfSlam{c}, std::invalid_argument);
  MrptEkfSlamOptions o;
  o.ic_chi2_quantile = 1.0;
  EXPECT_THROW(MrptEkfSlam(StaticContext(), o), std::invalid_argument);
  o = MrptEkfSlamOptions{};
  o.prune_after_steps = -1;
  EXPECT_THROW(MrptEkfSlam(StaticContext(), o), std::invalid_argument);
  filters::EstimatorContext no_motion = StaticContext();
  no_motion.motion.reset();
  EXPECT_THROW(MrptEkfSlam{no_motion}, std::invalid_argument);
}

TEST(AssociationOptions, ParsesAndPrintsNames) {
  for (AssociationMethod m : {AssociationMethod::kNearestNeighbour, AssociationMethod::kJcbb}) {
    EXPECT_EQ(ParseAssociationMethod(ToString(m), "f"), m);
  }
  for (AssociationMetric m :
       {AssociationMetric::kMahalanobis, AssociationMetric::kMatchingLikelihood}) {
    EXPECT_EQ(ParseAssociationMetric(ToString(m), "f"), m);
  }
  EXPECT_THROW(ParseAssociationMethod("jcb", "f"), std::invalid_argument);
  EXPECT_THROW(ParseAssociationMetric("maha", "f"), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference
