#include "reference/ceres/filter_association.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "reference/ceres/test_scenario.h"

namespace phdslam::reference {
namespace {

const Landmark kNone = Landmark::Constant(std::numeric_limits<double>::quiet_NaN());

TEST(LabelsFromAssociatedMeans, TracksLandmarksAcrossScans) {
  const Landmark a(10.0, 5.0);
  const Landmark b(30.0, -4.0);
  const std::vector<std::vector<Landmark>> means = {
      {a, kNone},
      {a + Vec2(0.1, 0.0), b},
      {b + Vec2(0.2, 0.0), a + Vec2(0.3, 0.1), kNone},
      {a + Vec2(0.3, 0.1) + Vec2(1.9, 0.0)},  // moved 1.9 m since its last association
      {a + Vec2(5.0, 0.0)},                   // too far: a new landmark
  };
  const auto labels = LabelsFromAssociatedMeans(means, 2.0);
  const std::vector<std::vector<int>> expected = {{0, -1}, {0, 1}, {1, 0, -1}, {0}, {2}};
  EXPECT_EQ(labels, expected);
}

TEST(LabelsFromAssociatedMeans, ALabelIsUsedOncePerScanClosestFirst) {
  const Landmark a(0.0, 0.0);
  const auto labels =
      LabelsFromAssociatedMeans({{a}, {a + Vec2(0.5, 0.0), a + Vec2(0.1, 0.0)}}, 2.0);
  EXPECT_EQ(labels[1], (std::vector<int>{1, 0}));
  EXPECT_THROW(LabelsFromAssociatedMeans({}, 0.0), std::invalid_argument);
}

TEST(LabelsFromAssociatedMeans, BirthPointsStartLabelsThatAssociationsContinue) {
  const Landmark p(4.0, 4.0);
  const std::vector<std::vector<Landmark>> means = {{kNone, kNone}, {p, kNone}, {kNone}};
  const std::vector<std::vector<Landmark>> births = {
      {p, Landmark(50.0, 0.0)}, {kNone, p + Vec2(0.05, 0.0)}, {kNone}};
  const auto labels = LabelsFromAssociatedMeans(means, 2.0, births);
  // The birth at p is continued by the association at p; the later birth next to it starts its
  // own label (births never continue one); a NaN without a birth point stays clutter.
  const std::vector<std::vector<int>> expected = {{0, 1}, {0, 2}, {-1}};
  EXPECT_EQ(labels, expected);
  EXPECT_THROW(LabelsFromAssociatedMeans(means, 2.0, {{p}}), std::invalid_argument);
}

/// A stand-in filter that associates every detection with its true landmark (read from the
/// hidden labels) and everything else with nothing.
class LabelFilter final : public filters::OnlineEstimator {
 public:
  LabelFilter(const datasets::Scenario& s, bool broken) : s_(s), broken_(broken) {}
  filters::StepOutput Step(const datasets::StepData&) override {
    filters::StepOutput out;
    for (int o : s_.steps[k_].origin) {
      out.association.push_back(o < 0 ? kNone : s_.truth.landmarks[static_cast<std::size_t>(o)]);
    }
    if (broken_ && k_ == 4) out.association.pop_back();
    out.pose = s_.truth.poses[k_];
    ++k_;
    return out;
  }
  [[nodiscard]] filters::MapEstimate Map() const override { return {}; }

 private:
  const datasets::Scenario& s_;
  bool broken_;
  std::size_t k_ = 0;
};

TEST(FilterThenSmooth, WithAPerfectFilterEqualsTheKnownAssociation) {
  testing::CircleScenarioOptions c;
  c.clutter_rate = 3.0;
  const datasets::Scenario s = testing::MakeCircleScenario(c);
  SmootherOptions o;
  o.compute_covariances = false;
  o.robust_loss = "none";
  const datasets::BatchResult known = BatchSmoother(o).Solve(s);
  FilterThenSmooth fs(std::make_unique<LabelFilter>(s, false), o);
  const datasets::BatchResult r = fs.Solve(s);
  ASSERT_EQ(r.map.means.size(), known.map.means.size());
  for (std::size_t k = 0; k < r.poses.size(); ++k) {
    EXPECT_LT((r.poses[k] - known.poses[k]).norm(), 1e-6);
  }
  EXPECT_GE(r.solve_seconds, fs.filter_seconds());
  // Clutter (unassociated by the filter) becomes single-detection birth labels, which the
  // smoother drops; every detection keeps its landmark.
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    for (std::size_t j = 0; j < s.steps[k].origin.size(); ++j) {
      EXPECT_GE(fs.labels()[k][j], 0);
      EXPECT_EQ(fs.smoother().association()[k][j] < 0, s.steps[k].origin[j] < 0);
    }
  }
  EXPECT_THROW(fs.Solve(s), std::logic_error);
}

TEST(FilterThenSmooth, RejectsAnAssociationOfTheWrongSize) {
  const datasets::Scenario s = testing::MakeCircleScenario({});
  FilterThenSmooth fs(std::make_unique<LabelFilter>(s, true), SmootherOptions{});
  EXPECT_THROW(fs.Solve(s), std::runtime_error);
  EXPECT_THROW(FilterThenSmooth(nullptr, SmootherOptions{}), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::reference
