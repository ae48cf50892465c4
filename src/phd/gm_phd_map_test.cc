#include "src/phd/gm_phd_map.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "src/core/angles.h"
#include "src/core/random.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::phd {
namespace {

models::SensorModel TestSensor() {
  models::SensorModel s;
  s.noise_cov << 0.64, 0.0, 0.0, 2.7416e-5;
  return s;
}

// Independent re-derivation of one detection term and its posterior (docs/algorithms/phd-slam.md
// section 3.2).
struct Expected {
  double log_gain;
  Vec2 mean;
  Mat2 cov;
  double nis;  // nu' S^-1 nu
};
Expected DetectionTerm(const Pose& x, const GaussianComponent& c, const Measurement& z,
                       const Mat2& r, double pd) {
  const double dx = c.mean(0) - x(0);
  const double dy = c.mean(1) - x(1);
  const double q = dx * dx + dy * dy;
  Mat2 h;
  h << dx / std::sqrt(q), dy / std::sqrt(q), -dy / q, dx / q;
  const Mat2 s = h * c.cov * h.transpose() + r;
  Vec2 nu = z - Vec2(std::sqrt(q), std::atan2(dy, dx) - x(2));
  nu(1) = WrapAngle(nu(1));
  const double d2 = nu.transpose() * s.inverse() * nu;
  const Mat2 k = c.cov * h.transpose() * s.inverse();
  return {std::log(pd) + c.log_weight - std::log(2 * std::numbers::pi) -
              0.5 * std::log(s.determinant()) - 0.5 * d2,
          c.mean + k * nu, (Mat2::Identity() - k * h) * c.cov, d2};
}

TEST(GmPhdMapUpdate, TwoComponentExampleMatchesHandComputation) {
  const models::SensorModel sensor = TestSensor();
  const MapParams params;
  const Pose x(1.0, 2.0, 0.3);
  GmPhdMap map;
  const GaussianComponent a{Landmark(20.0, 8.0), Mat2::Identity() * 0.5, std::log(0.9)};
  const GaussianComponent b{Landmark(21.0, 9.5), Mat2::Identity() * 2.0, std::log(0.4)};
  map.SetActive({a, b});
  // z0 near both components, z1 far from everything.
  const Measurement z0 = models::PredictMeasurement(x, Landmark(20.3, 8.4));
  const Measurement z1(100.0, -1.0);
  const std::vector<Measurement> zs = {z0, z1};

  const PhdUpdateResult res = map.Update(x, zs, sensor, params);

  const Expected ea = DetectionTerm(x, a, z0, sensor.noise_cov, 0.95);
  const Expected eb = DetectionTerm(x, b, z0, sensor.noise_cov, 0.95);
  const double lc = sensor.ClutterIntensity();
  const double c0 = std::log(lc + std::exp(ea.log_gain) + std::exp(eb.log_gain));
  EXPECT_NEAR(res.log_likelihood, c0 + std::log(lc), 1e-10);
  ASSERT_EQ(res.ungated.size(), 1u);
  EXPECT_EQ(res.ungated[0], 1);

  const auto& act = map.active();
  ASSERT_EQ(act.size(), 4u);  // two misdetected copies, then z0 x {a, b}
  EXPECT_NEAR(act[0].log_weight, std::log(0.9 * 0.05), 1e-12);
  EXPECT_NEAR(act[1].log_weight, std::log(0.4 * 0.05), 1e-12);
  EXPECT_EQ(act[0].mean, a.mean);
  EXPECT_NEAR(act[2].log_weight, ea.log_gain - c0, 1e-10);
  EXPECT_NEAR(act[3].log_weight, eb.log_gain - c0, 1e-10);
  EXPECT_LT((act[2].mean - ea.mean).norm(), 1e-9);
  EXPECT_LT((act[3].cov - eb.cov).norm(), 1e-9);
  // Detection weights of one measurement plus clutter share sum to one.
  EXPECT_NEAR(std::exp(act[2].log_weight) + std::exp(act[3].log_weight) + lc / std::exp(c0), 1.0,
              1e-12);
  // NIS: z0 is explained best by the component with the larger detection term, which beats
  // clutter here; z1 gated with nothing and is not counted.
  const Expected& best = ea.log_gain > eb.log_gain ? ea : eb;
  ASSERT_GT(best.log_gain, std::log(lc));
  EXPECT_EQ(res.nis_count, 1);
  EXPECT_NEAR(res.nis_sum, best.nis, 1e-9);
}

TEST(GmPhdMapUpdate, EmptyScanChangesNothingAndOutOfFovComponentsAreUntouched) {
  const models::SensorModel sensor = TestSensor();
  GmPhdMap map;
  const GaussianComponent behind{Landmark(-50.0, 0.0), Mat2::Identity(), -1.0};
  map.SetActive({behind});
  const PhdUpdateResult none = map.Update(Pose::Zero(), {}, sensor, MapParams{});
  EXPECT_EQ(none.log_likelihood, 0.0);
  EXPECT_EQ(map.active()[0].log_weight, -1.0);
  const std::vector<Measurement> zs = {Measurement(10.0, 0.0)};
  const PhdUpdateResult one = map.Update(Pose::Zero(), zs, sensor, MapParams{});
  EXPECT_NEAR(one.log_likelihood, std::log(sensor.ClutterIntensity()), 1e-14);
  ASSERT_EQ(map.active().size(), 1u);
  EXPECT_EQ(map.active()[0].log_weight, -1.0);  // pD = 0: unchanged
  EXPECT_EQ(one.ungated, std::vector<int>{0});
}

TEST(GmPhdMapUpdate, ExactLikelihoodOptionSubtractsExpectedDetections) {
  const models::SensorModel sensor = TestSensor();
  MapParams exact;
  exact.reference_omit_missed_detection_mass = false;
  GmPhdMap a;
  GmPhdMap b;
  const GaussianComponent c{Landmark(30.0, 0.0), Mat2::Identity(), std::log(0.7)};
  a.SetActive({c});
  b.SetActive({c});
  const std::vector<Measurement> zs = {Measurement(30.0, 0.0)};
  const double ref = a.Update(Pose::Zero(), zs, sensor, MapParams{}).log_likelihood;
  const double full = b.Update(Pose::Zero(), zs, sensor, exact).log_likelihood;
  EXPECT_NEAR(ref - full, 0.95 * 0.7, 1e-12);
}

TEST(PruneAndMerge, MergesByLeadingCovarianceWithDoubleMembershipQuirk) {
  MapParams params;
  const GaussianComponent a{Landmark(0.0, 0.0), Mat2::Identity() * 0.01, std::log(0.9)};
  const GaussianComponent b{Landmark(5.0, 0.0), Mat2::Identity(), std::log(0.8)};
  const GaussianComponent c{Landmark(0.5, 0.0), Mat2::Identity() * 0.02, std::log(0.7)};
  // Sorted: a, b, c. a's cluster (distance with a's covariance): c (d2 = 25) but not b (2500).
  // b's cluster: c again (d2 = 20.25), because c is not checked for earlier membership.
  const auto merged = PruneAndMerge({c, b, a}, params);
  ASSERT_EQ(merged.size(), 2u);
  const double wa = 0.9;
  const double wc = 0.7;
  EXPECT_NEAR(merged[0].log_weight, std::log(wa + wc), 1e-12);
  const Vec2 mean_ac = (wa * a.mean + wc * c.mean) / (wa + wc);
  EXPECT_LT((merged[0].mean - mean_ac).norm(), 1e-12);
  const Mat2 cov_ac = (wa * (a.cov + (mean_ac - a.mean) * (mean_ac - a.mean).transpose()) +
                       wc * (c.cov + (mean_ac - c.mean) * (mean_ac - c.mean).transpose())) /
                      (wa + wc);
  EXPECT_LT((merged[0].cov - cov_ac).norm(), 1e-12);
  EXPECT_NEAR(merged[1].log_weight, std::log(0.8 + 0.7), 1e-12);

  params.reference_merge_double_membership = false;
  const auto single = PruneAndMerge({c, b, a}, params);
  ASSERT_EQ(single.size(), 2u);
  EXPECT_NEAR(single[1].log_weight, std::log(0.8), 1e-12);
  EXPECT_EQ(single[1].mean, b.mean);

  // Vo & Ma distance (candidate's covariance): b is 25 from a with b's covariance and c 12.5,
  // so everything joins a's cluster.
  params.reference_merge_leading_covariance = false;
  params.reference_merge_double_membership = true;
  const auto vo_ma = PruneAndMerge({c, b, a}, params);
  ASSERT_EQ(vo_ma.size(), 1u);
  EXPECT_NEAR(vo_ma[0].log_weight, std::log(0.9 + 0.8 + 0.7), 1e-12);
}

TEST(PruneAndMerge, PrunesButKeepsTheLeaderAndKillsWideComponents) {
  MapParams params;
  const GaussianComponent tiny1{Landmark(0.0, 0.0), Mat2::Identity(), std::log(1e-8)};
  const GaussianComponent tiny2{Landmark(100.0, 0.0), Mat2::Identity(), std::log(1e-7)};
  const auto kept = PruneAndMerge({tiny1, tiny2}, params);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_NEAR(kept[0].log_weight, std::log(1e-7), 1e-12);

  const GaussianComponent wide{Landmark(0.0, 0.0), Mat2::Identity() * 30.0, 0.0};
  const auto killed = PruneAndMerge({wide}, params);
  EXPECT_EQ(killed[0].log_weight, params.spread_kill_log_weight);
  params.reference_spread_kill = false;
  EXPECT_EQ(PruneAndMerge({wide}, params)[0].log_weight, 0.0);
}

TEST(PruneAndMerge, KeepsTheOrderOfAStableSortByDescendingWeight) {
  // Components 1 km apart never merge, so the output is the input in sorted order. Weights from
  // a set of four give ties, which keep their input order; lengths up to 40 cover both the short
  // lists' insertion and the long lists' stable_sort.
  MapParams params;
  params.prune_log_weight = -1e300;
  RandomStream rng(12345);
  for (int length = 1; length <= 40; ++length) {
    for (int trial = 0; trial < 50; ++trial) {
      std::vector<GaussianComponent> components;
      components.reserve(static_cast<std::size_t>(length));
      for (int i = 0; i < length; ++i) {
        const double tier = std::floor(rng.Uniform(0.0, 4.0));  // 0, 1, 2 or 3
        components.push_back({Landmark(1000.0 * i, 0.0), Mat2::Identity(), -1.0 - tier});
      }
      std::vector<GaussianComponent> expected = components;
      std::stable_sort(expected.begin(), expected.end(),
                       [](const GaussianComponent& a, const GaussianComponent& b) {
                         return a.log_weight > b.log_weight;
                       });
      const std::vector<GaussianComponent> merged = PruneAndMerge(components, params);
      ASSERT_EQ(merged.size(), expected.size());
      for (std::size_t k = 0; k < merged.size(); ++k) {
        ASSERT_EQ(merged[k].mean(0), expected[k].mean(0)) << "length " << length << ", " << k;
      }
    }
  }
}

TEST(GmPhdMapReduce, ActivePassiveSplitFollowsTheEnlargedFov) {
  const models::SensorModel sensor = TestSensor();
  const MapParams params;
  GmPhdMap map;
  const GaussianComponent inside{Landmark(155.0, 0.0), Mat2::Identity(), -1.0};  // buffer zone
  const GaussianComponent leaving{Landmark(0.0, -200.0), Mat2::Identity(), -2.0};
  const GaussianComponent weak{Landmark(0.0, -300.0), Mat2::Identity(), -13.9};
  const GaussianComponent back{Landmark(50.0, 0.0), Mat2::Identity(), -3.0};
  const GaussianComponent away{Landmark(-500.0, 0.0), Mat2::Identity(), -4.0};
  map.SetActive({inside, leaving, weak});
  map.SetPassive({back, away});
  map.Reduce(Pose::Zero(), sensor, params);
  ASSERT_EQ(map.active().size(), 2u);
  EXPECT_EQ(map.active()[0].mean, inside.mean);
  EXPECT_EQ(map.active()[1].mean, back.mean);
  ASSERT_EQ(map.passive().size(), 2u);  // weak one deleted
  EXPECT_EQ(map.passive()[0].mean, away.mean);
  EXPECT_EQ(map.passive()[1].mean, leaving.mean);
  const auto est = map.Estimate(std::log(0.05 * 0.05));
  EXPECT_EQ(est.size(), 4u);
  EXPECT_EQ(map.Estimate(-2.5).size(), 2u);
}

TEST(GmPhdMapBirths, UseTheInverseModelAtTheGivenPose) {
  const models::SensorModel sensor = TestSensor();
  GmPhdMap map;
  const Pose x(1.0, 1.0, 0.5);
  const std::vector<Measurement> zs = {Measurement(10.0, 0.2)};
  map.AddBirths(x, zs, sensor.noise_cov, MapParams{});
  ASSERT_EQ(map.active().size(), 1u);
  EXPECT_LT((map.active()[0].mean - models::InverseMeasurement(x, zs[0])).norm(), 1e-12);
  EXPECT_NEAR(map.active()[0].log_weight, std::log(1e-6), 1e-12);
}

// Passive storage is shared between copies and copied only where a copy changes it; the passive
// order and the re-entering order are those of one flat list.
TEST(GmPhdMapReduce, PassiveChunksAreSharedAndCopiedOnWrite) {
  const models::SensorModel sensor = TestSensor();
  const MapParams params;
  std::vector<GaussianComponent> passive;
  // 300 far components (5 chunks, all beyond the enlarged range), then 100 near the pose.
  for (int i = 0; i < 300; ++i) {
    passive.push_back({Landmark(1000.0 + i, 500.0), Mat2::Identity(), -0.01 * i});
  }
  for (int i = 0; i < 100; ++i) {
    passive.push_back({Landmark(-150.0 + 3.0 * i, 20.0), Mat2::Identity(), -0.02 * i});
  }
  GmPhdMap original;
  original.SetPassive(passive);
  GmPhdMap copy = original;
  ByteTally shared;
  original.CountBytes(shared);
  const std::size_t one = shared.bytes();
  copy.CountBytes(shared);
  EXPECT_LT(shared.bytes(), one + one / 10);  // a copy adds only its chunk pointers

  copy.Reduce(Pose::Zero(), sensor, params);
  // The original is untouched.
  const std::vector<GaussianComponent> before = original.passive();
  ASSERT_EQ(before.size(), passive.size());
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_EQ(before[i].mean, passive[i].mean);
  // The copy: re-entering components moved to the active list in passive order, the rest kept
  // in order, as the flat-list split gives.
  const models::FovView fov(sensor, Pose::Zero());
  std::vector<GaussianComponent> expect_active;
  std::vector<GaussianComponent> expect_passive;
  for (const GaussianComponent& c : passive) {
    (fov.InEnlargedFov(c.mean) ? expect_active : expect_passive).push_back(c);
  }
  ASSERT_GT(expect_active.size(), 10u);
  ASSERT_EQ(copy.active().size(), expect_active.size());
  for (std::size_t i = 0; i < expect_active.size(); ++i) {
    EXPECT_EQ(copy.active()[i].mean, expect_active[i].mean);
  }
  const std::vector<GaussianComponent> after = copy.passive();
  ASSERT_EQ(after.size(), expect_passive.size());
  EXPECT_EQ(copy.passive_size(), expect_passive.size());
  for (std::size_t i = 0; i < after.size(); ++i) EXPECT_EQ(after[i].mean, expect_passive[i].mean);
  // The far chunks are still shared: both maps together hold far less than two maps.
  ByteTally both;
  original.CountBytes(both);
  copy.CountBytes(both);
  EXPECT_LT(both.bytes(), one + one / 2);
}

}  // namespace
}  // namespace phdslam::phd
