#include "reference/ceres/particle_lineage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <vector>

#include "reference/ceres/start_trajectory.h"
#include "reference/ceres/test_scenario.h"
#include "src/filters/phd_slam_family.h"

namespace phdslam::reference {
namespace {

Pose At(double x) { return {x, 0.0, 0.0}; }

// Two particles, one near x = 0 and one near x = 10, whose weights take turns: the per-step
// estimate (the highest weight of each step) jumps between them, the best final particle's path
// does not. Step 1 resamples into {1, 1}: both descend from the particle near 10 from then on.
TEST(ParticleLineage, FollowsTheAncestryOfTheBestFinalParticleWhereTheEstimateSwitches) {
  ParticleLineage l;
  l.AddParticle(0, 0, At(0.0), -1.0);
  l.AddParticle(0, 1, At(10.0), -2.0);  // estimate: 0.0
  l.AddParticle(1, 0, At(1.0), -1.0);
  l.AddParticle(1, 1, At(11.0), -3.0);  // estimate: 1.0
  l.AddResampling(1, {1, 1});
  l.AddParticle(2, 0, At(12.0), -2.0);
  l.AddParticle(2, 1, At(12.5), -1.0);  // estimate: 12.5, a jump of 11.5 from the last one
  const std::vector<Pose> path = l.BestFinalPath();
  ASSERT_EQ(path.size(), 3U);
  EXPECT_EQ(path[2], At(12.5));
  EXPECT_EQ(path[1], At(11.0));  // the resampled parent, not step 1's estimate (1.0)
  EXPECT_EQ(path[0], At(10.0));  // no resampling at step 0: the same index
}

TEST(ParticleLineage, TakesTheFirstOnTiesAndRejectsOutOfOrderRecords) {
  ParticleLineage l;
  EXPECT_TRUE(l.BestFinalPath().empty());
  l.AddParticle(0, 0, At(1.0), -1.0);
  l.AddParticle(0, 1, At(2.0), -1.0);
  EXPECT_EQ(l.BestFinalPath().front(), At(1.0));
  EXPECT_THROW(l.AddParticle(0, 3, At(0.0), 0.0), std::invalid_argument);  // skips particle 2
  EXPECT_THROW(l.AddParticle(2, 0, At(0.0), 0.0), std::invalid_argument);  // skips step 1
  EXPECT_THROW(l.AddResampling(0, {0, 2}), std::invalid_argument);         // no particle 2
  EXPECT_THROW(l.AddResampling(1, {0, 1}), std::invalid_argument);         // step 1 not recorded
  l.AddParticle(1, 0, At(3.0), 0.0);
  EXPECT_THROW(l.AddResampling(0, {0, 1}), std::invalid_argument);  // not the last step
  // Step 1 has one particle after a step of two without resampling: particle 0 descends from 0.
  EXPECT_EQ(l.BestFinalPath()[0], At(1.0));
}

// PHD-SLAM 3.0 with 5 particles on the circle with clutter, resampling at ESS <= 0.9 N: the path
// ends at the filter's last estimate, is a particle's pose at every step, and
// SmoothFromEstimatorStart starts from it.
TEST(ParticleLineage, RecordsAPhdSlamRunAndStartsTheSmootherFromTheBestPath) {
  testing::CircleScenarioOptions c;
  c.clutter_rate = 3.0;
  c.steps = 60;
  const datasets::Scenario s = testing::MakeCircleScenario(c);
  filters::PhdSlamParams params;
  params.particles = 5;
  params.ess_threshold = 0.9;  // resample often, so that the ancestry is exercised
  auto filter = filters::MakePhdSlam("phd3", s.PublicContext(), params, 11);
  LineageObserver<filters::PhdParticle> observer;
  filter->SetObserver(&observer);
  std::vector<std::vector<Pose>> particle_poses;
  Pose last_estimate = Pose::Zero();
  int resampled = 0;
  for (const auto& step : s.steps) {
    const filters::StepOutput out = filter->Step(step.data);
    last_estimate = out.pose;
    resampled += out.diag.resampled ? 1 : 0;
    particle_poses.emplace_back();
    for (const auto& [pose, log_weight] : filter->ParticleStates()) {
      particle_poses.back().push_back(pose);
    }
  }
  const std::vector<Pose> path = observer.lineage().BestFinalPath();
  ASSERT_EQ(path.size(), s.steps.size());
  // An ancestor survived its step's resampling: its pose is among the particles after the step.
  for (std::size_t k = 0; k < path.size(); ++k) {
    EXPECT_NE(std::find(particle_poses[k].begin(), particle_poses[k].end(), path[k]),
              particle_poses[k].end())
        << "step " << k;
  }
  EXPECT_EQ(path.back(), last_estimate);
  EXPECT_GT(resampled, 0);  // the ancestry is exercised

  SmootherOptions o;
  o.association = AssociationMode::kUnknown;
  o.compute_covariances = false;
  o.start_from = StartTrajectory::kPhd3;
  o.start_path = StartPath::kBestParticlePath;
  SmoothFromEstimatorStart started(filters::MakePhdSlam("phd3", s.PublicContext(), params, 11), o);
  const datasets::BatchResult r = started.Solve(s);
  EXPECT_EQ(started.start(), path);  // the same stream gives the same run and path
  EXPECT_EQ(r.poses.size(), s.steps.size());
  EXPECT_LT(testing::PositionRmse(s, r.poses), 1.0);

  // A filter seen only as an OnlineEstimator has no particles to trace.
  std::unique_ptr<filters::OnlineEstimator> plain =
      filters::MakePhdSlam("phd3", s.PublicContext(), params, 11);
  EXPECT_THROW(SmoothFromEstimatorStart(std::move(plain), o), std::invalid_argument);
  o.start_from = StartTrajectory::kDeadReckoning;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference
