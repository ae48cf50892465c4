#include "reference/ceres/landmark_association.h"

#include <gtest/gtest.h>

#include <map>

#include "reference/ceres/batch_smoother.h"
#include "reference/ceres/test_scenario.h"

namespace phdslam::reference {
namespace {

using testing::CircleScenarioOptions;
using testing::MakeCircleScenario;

AssociationOptions OptionsFor(const datasets::Scenario& s) {
  AssociationOptions o;
  o.measurement_cov = s.sensor.noise_cov;
  o.sensor = s.sensor;
  return o;
}

/// Expects `association` to equal the hidden labels up to a renumbering of the landmarks, with
/// clutter unassociated; returns the number of measurements that break this.
int CountLabelMismatches(const datasets::Scenario& s, const Association& association) {
  std::map<int, int> truth_of;
  int mismatches = 0;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    for (std::size_t j = 0; j < s.steps[k].origin.size(); ++j) {
      const int a = association[k][j];
      const int t = s.steps[k].origin[j];
      if (a == kUnassociated || t < 0) {
        mismatches += (a == kUnassociated) != (t < 0) ? 1 : 0;
        continue;
      }
      const auto [it, inserted] = truth_of.emplace(a, t);
      if (!inserted && it->second != t) ++mismatches;
    }
  }
  return mismatches;
}

TEST(SequentialAssociation, NoiseFreeDataIsAssociatedExactly) {
  CircleScenarioOptions c;
  c.noise = false;
  const datasets::Scenario s = MakeCircleScenario(c);
  const AssociatedMap m = SequentialAssociation(s, ScenarioOdometry(s, {}), OptionsFor(s));
  EXPECT_EQ(m.landmarks.size(), 20u);
  EXPECT_EQ(CountLabelMismatches(s, m.association), 0);
  EXPECT_EQ(m.dropped, 0);
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    EXPECT_LT((m.poses[k] - s.truth.poses[k]).norm(), 1e-6);
  }
}

TEST(SequentialAssociator, ConfirmedAndCorrectWorkOnThePrefix) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  SequentialAssociator a(s, ScenarioOdometry(s, {}), OptionsFor(s));
  a.AdvanceTo(30);
  EXPECT_EQ(a.steps_done(), 30u);
  std::vector<int> ids;
  const AssociatedMap partial = a.Confirmed(&ids);
  ASSERT_EQ(partial.poses.size(), 30u);
  ASSERT_EQ(partial.association.size(), 30u);
  ASSERT_EQ(ids.size(), partial.landmarks.size());
  EXPECT_GT(ids.size(), 3u);
  // Moving every confirmed landmark and pose to the truth is reflected in what follows.
  std::vector<Pose> poses(s.truth.poses.begin(), s.truth.poses.begin() + 30);
  std::vector<Landmark> means;
  for (std::size_t n = 0; n < ids.size(); ++n) {
    int label = -1;
    for (std::size_t k = 0; k < 30 && label < 0; ++k) {
      for (std::size_t j = 0; j < partial.association[k].size(); ++j) {
        if (partial.association[k][j] == static_cast<int>(n)) label = s.steps[k].origin[j];
      }
    }
    ASSERT_GE(label, 0);
    means.push_back(s.truth.landmarks[static_cast<std::size_t>(label)]);
  }
  a.Correct(poses, ids, means);
  std::vector<int> ids_after;
  const AssociatedMap corrected = a.Confirmed(&ids_after);
  EXPECT_EQ(ids_after, ids);
  EXPECT_EQ(corrected.landmarks, means);
  EXPECT_EQ(corrected.poses, poses);
  EXPECT_THROW(a.Correct(std::vector<Pose>(3), ids, means), std::invalid_argument);
  a.AdvanceTo(1000);  // clamped
  EXPECT_EQ(a.steps_done(), s.steps.size());
}

TEST(Reassociate, MergesADuplicatedLandmark) {
  const datasets::Scenario s = MakeCircleScenario(CircleScenarioOptions{});
  // Landmark 3 is held twice, 10 cm apart around its true position: with measurement noise each
  // copy is the nearer one for about half of the detections, so both keep support, and they are
  // never seen at the same scan.
  std::vector<Landmark> landmarks = s.truth.landmarks;
  landmarks.push_back(landmarks[3] + Vec2(0.05, 0.0));
  landmarks[3] -= Vec2(0.05, 0.0);
  Association previous;
  int flip = 0;
  for (const auto& step : s.steps) {
    std::vector<int> a = step.origin;
    for (int& i : a) {
      if (i == 3 && (flip++ % 2) == 1) i = 20;
    }
    previous.push_back(a);
  }
  const AssociatedMap m = Reassociate(s, s.truth.poses, landmarks, previous, OptionsFor(s));
  EXPECT_EQ(m.merged, 1);
  ASSERT_EQ(m.landmarks.size(), 20u);
  EXPECT_LT(CountLabelMismatches(s, m.association), 5);  // detections outside the 0.999 gate
  // The information-weighted mean of the two copies.
  EXPECT_LT((m.landmarks[3] - s.truth.landmarks[3]).norm(), 0.05);
}

TEST(Reassociate, KeepsTwoCloseLandmarksSeenTogetherApart) {
  CircleScenarioOptions c;
  c.noise = false;
  c.landmarks = 40;  // ring neighbours 3.9 m apart, seen at the same steps
  const datasets::Scenario s = MakeCircleScenario(c);
  AssociationOptions o = OptionsFor(s);
  o.merge_position_std = 5.0;  // a merge gate far wider than their distance
  std::vector<std::vector<int>> previous;
  for (const auto& step : s.steps) previous.push_back(step.origin);
  const AssociatedMap m = Reassociate(s, s.truth.poses, s.truth.landmarks, previous, o);
  EXPECT_EQ(m.merged, 0);
  EXPECT_EQ(m.landmarks.size(), 40u);
  EXPECT_EQ(CountLabelMismatches(s, m.association), 0);
}

TEST(Reassociate, LeavesClutterUnassociatedAtTheTruth) {
  CircleScenarioOptions c;
  c.clutter_rate = 5.0;
  const datasets::Scenario s = MakeCircleScenario(c);
  std::vector<std::vector<int>> previous;
  for (const auto& step : s.steps) previous.push_back(step.origin);
  const AssociatedMap m = Reassociate(s, s.truth.poses, s.truth.landmarks, previous, OptionsFor(s));
  EXPECT_EQ(m.landmarks.size(), 20u);
  EXPECT_GT(m.born, 300);        // every clutter point starts a landmark ...
  EXPECT_EQ(m.dropped, m.born);  // ... and none has support
  // A few detections fall outside the 0.999 gate or lose to clutter; clutter rarely wins one.
  EXPECT_LT(CountLabelMismatches(s, m.association), 15);
}

TEST(CountObservations, CountsAndRejectsBadIndices) {
  const Association a = {{0, -1, 1}, {1, 1}, {}};
  EXPECT_EQ(CountObservations(a, 2), (std::vector<int>{1, 3}));
  EXPECT_THROW(CountObservations(a, 1), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference
