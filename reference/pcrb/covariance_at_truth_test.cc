// The known-association graph's marginal covariances, evaluated by Ceres at the truth (no solve),
// equal the smoothing bound of reference/pcrb (docs/algorithms/pcrb.md section 3): the bound is
// the inverse Fisher information of the same graph, and the graph's factors are the exact
// likelihoods of the odometry and the detections. The only difference is the control-space
// odometry factor's softened no-sideways-slip constraint (lateral_std, the odometry floor's
// position_std), which the bound takes as exact.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "reference/ceres/batch_smoother.h"
#include "reference/ceres/factor_graph.h"
#include "reference/ceres/landmark_association.h"
#include "reference/ceres/test_scenario.h"
#include "reference/pcrb/filtering_bound.h"
#include "reference/pcrb/linearise.h"
#include "reference/pcrb/smoothing_bound.h"

namespace phdslam::reference::pcrb {
namespace {

Association KnownAssociation(const datasets::Scenario& s) {
  Association a(s.steps.size());
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    for (int origin : s.steps[k].origin) a[k].push_back(origin >= 0 ? origin : kUnassociated);
  }
  return a;
}

double RelativeDifference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / std::max(a.norm(), b.norm());
}

TEST(CovarianceAtTruth, KnownAssociationGraphEqualsTheSmoothingBound) {
  testing::CircleScenarioOptions o;
  o.steps = 80;
  o.landmarks = 16;
  o.clutter_rate = 0.0;  // the conditioned bound's clutter factor is then 1 exactly
  const datasets::Scenario s = testing::MakeCircleScenario(o);

  const OdometryNoiseFloor floor;
  const std::vector<OdometryIncrement> increments = ScenarioOdometry(s, floor);
  const OdometrySpec spec{&increments, floor, /*control_space=*/true};
  std::vector<Pose> poses = s.truth.poses;
  std::vector<Landmark> landmarks = s.truth.landmarks;
  FactorGraph graph(s, spec, KnownAssociation(s), nullptr, &poses, &landmarks);
  std::vector<std::optional<Mat3>> pose_covs;
  std::vector<Mat2> landmark_covs;
  ASSERT_TRUE(graph.Covariances(1, &pose_covs, &landmark_covs));

  const pcrb::LinearisedSlam model = pcrb::Linearise(s, pcrb::PcrbParams{}, 1, "test");
  const pcrb::FilteringBound filtering = pcrb::ComputeFilteringBound(model);
  const std::vector<Mat3> bound = pcrb::ComputeSmoothingBound(model, filtering);

  ASSERT_EQ(pose_covs.size(), bound.size());
  double worst_pose = 0.0;
  for (std::size_t k = 1; k < bound.size(); ++k) {
    ASSERT_TRUE(pose_covs[k].has_value()) << "step " << k;
    worst_pose = std::max(worst_pose, RelativeDifference(*pose_covs[k], bound[k]));
  }
  double worst_landmark = 0.0;
  int compared = 0;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    if (!filtering.landmark_seen[i] || !graph.HasLandmark(i)) continue;
    worst_landmark =
        std::max(worst_landmark, RelativeDifference(landmark_covs[i], filtering.landmark_covs[i]));
    ++compared;
  }
  EXPECT_GT(compared, 8);
  EXPECT_LT(worst_pose, 1e-4);
  EXPECT_LT(worst_landmark, 1e-4);
}

}  // namespace
}  // namespace phdslam::reference::pcrb
