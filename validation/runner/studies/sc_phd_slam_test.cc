#include "src/filters/sc_phd_slam.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "datasets/scenario_generator.h"
#include "src/core/angles.h"
#include "src/core/log_sum_exp.h"
#include "src/models/pose_propagation.h"
#include "src/models/velocity_motion_model.h"
#include "validation/runner/registry/scenario_defaults.h"
#include "validation/runner/studies/parent_weights.h"

namespace phdslam::filters {
namespace {

using phd::GaussianComponent;
using phd::GmPhdMap;

// A short generated scenario (paper sensor and noise) with clutter.
datasets::Scenario SmallScenario(std::uint64_t seed, int steps = 60) {
  datasets::GeneratorOptions o;
  o.steps = steps;
  o.landmarks = 40;
  o.corridor_half_width = 60.0;
  o.initial_pose = Pose(5.0, -3.0, 0.2);
  return datasets::GenerateScenario(o, seed);
}

void ExpectSameComponents(const std::vector<GaussianComponent>& a,
                          const std::vector<GaussianComponent>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].mean, b[i].mean) << what << " component " << i;
    EXPECT_EQ(a[i].cov, b[i].cov) << what << " component " << i;
    EXPECT_EQ(a[i].log_weight, b[i].log_weight) << what << " component " << i;
  }
}

// log N(z; h(m, x), Hm P Hm^T + R) written out with the range-bearing formulas of
// docs/algorithms/models.md section 3.1, an explicit 2x2 determinant and inverse, and the gate;
// nullopt-like NaN when the pair does not gate.
double HandLogGaussian(const Pose& x, const GaussianComponent& c, const Measurement& z,
                       const Mat2& r, double gate) {
  const double dx = c.mean(0) - x(0);
  const double dy = c.mean(1) - x(1);
  const double q = dx * dx + dy * dy;
  const double range = std::sqrt(q);
  Mat2 hm;
  hm << dx / range, dy / range, -dy / q, dx / q;
  const Mat2 s = hm * c.cov * hm.transpose() + r;
  const double det = s(0, 0) * s(1, 1) - s(0, 1) * s(1, 0);
  Mat2 s_inv;
  s_inv << s(1, 1), -s(0, 1), -s(1, 0), s(0, 0);
  s_inv /= det;
  Vec2 nu = z - Vec2(range, std::atan2(dy, dx) - x(2));
  nu(1) = std::remainder(nu(1), 2.0 * std::numbers::pi);
  const double d2 = nu.dot(s_inv * nu);
  if (!(d2 < gate)) return std::nan("");
  return -std::log(2.0 * std::numbers::pi) - 0.5 * std::log(det) - 0.5 * d2;
}

// The single-cluster multi-object log-likelihood by hand: -sum pD w (when included) plus
// sum_j log(lambda_c + sum_i pD w_i N(z_j; ...)) over gated pairs; pD is the sensor's constant
// pD inside the FOV, computed here from range and bearing directly.
double HandLogLikelihood(const Pose& x, const std::vector<GaussianComponent>& components,
                         const std::vector<Measurement>& z, const models::SensorModel& sensor,
                         bool include_missed_mass) {
  std::vector<double> pd(components.size(), 0.0);
  double missed = 0.0;
  for (std::size_t i = 0; i < components.size(); ++i) {
    const Vec2 d = components[i].mean - x.head<2>();
    const double bearing = std::remainder(std::atan2(d(1), d(0)) - x(2), 2.0 * std::numbers::pi);
    if (d.norm() <= sensor.fov_range && std::abs(bearing) <= sensor.fov_half_angle) {
      pd[i] = sensor.pd_max;
    }
    missed += pd[i] * std::exp(components[i].log_weight);
  }
  double total = include_missed_mass ? -missed : 0.0;
  for (const Measurement& zj : z) {
    double sum =
        sensor.clutter_rate / (sensor.fov_half_angle * sensor.fov_range * sensor.fov_range);
    for (std::size_t i = 0; i < components.size(); ++i) {
      if (pd[i] == 0.0) continue;
      const double lg = HandLogGaussian(x, components[i], zj, sensor.noise_cov, 41.4465);
      if (!std::isnan(lg)) sum += pd[i] * std::exp(components[i].log_weight + lg);
    }
    total += std::log(sum);
  }
  return total;
}

models::SensorModel PaperSensor() {
  models::SensorModel s;
  s.noise_cov = Vec2(0.8 * 0.8, std::pow(DegToRad(0.3), 2)).asDiagonal();
  return s;
}

// Two components ahead of the vehicle, a third behind it (pD = 0).
std::vector<GaussianComponent> TwoComponentMap() {
  std::vector<GaussianComponent> c(3);
  c[0] = {Landmark(20.0, 1.0), Vec2(1.0, 0.5).asDiagonal(), std::log(0.8)};
  c[1] = {Landmark(21.0, 2.5), Vec2(0.7, 1.2).asDiagonal(), std::log(0.6)};
  c[2] = {Landmark(-30.0, 0.0), Mat2::Identity(), std::log(0.9)};
  return c;
}

TEST(ScPhdSlamParams, DefaultsAreThePapers) {
  const ScPhdSlamParams p;
  EXPECT_EQ(p.particles, 1);
  EXPECT_EQ(p.shotgun, 4);
  EXPECT_DOUBLE_EQ(p.map.birth_log_weight, std::log(0.01));
  EXPECT_FALSE(p.map.reference_births_from_ungated_only);
  EXPECT_FALSE(p.map.reference_omit_missed_detection_mass);
  EXPECT_EQ(p.pose_regularisation, Mat3(Vec3(1e-9, 1e-9, 1e-18).asDiagonal()));
  EXPECT_DOUBLE_EQ(p.map.merge_threshold, 50.0);
  ScPhdSlamParams vp;
  ApplyJson(validation::ScenarioParameterDefaults("victoria-park", "scphd"), vp);
  EXPECT_DOUBLE_EQ(vp.map.merge_threshold, 10.0);
}

TEST(ScPhdSlamParams, JsonRoundTripAndErrors) {
  ScPhdSlamParams p;
  ApplyJson({{"particles", 7},
             {"shotgun", 3},
             {"birth_log_weight", -3.0},
             {"prediction", "linearised-gaussian"},
             {"empty_scan_update", false},
             {"pose_regularisation", {1e-6, 2e-6, 3e-9}},
             {"reference_births_from_ungated_only", true}},
            p);
  EXPECT_EQ(p.particles, 7);
  EXPECT_EQ(p.shotgun, 3);
  EXPECT_EQ(p.map.birth_log_weight, -3.0);
  EXPECT_EQ(p.prediction, ScPredictionSampling::kLinearisedGaussian);
  EXPECT_FALSE(p.empty_scan_update);
  EXPECT_EQ(p.pose_regularisation(1, 1), 2e-6);
  EXPECT_TRUE(p.map.reference_births_from_ungated_only);
  ScPhdSlamParams q;
  ApplyJson(ToJson(p), q);
  EXPECT_EQ(ToJson(q), ToJson(p));

  const auto message = [](const nlohmann::json& j) {
    ScPhdSlamParams r;
    try {
      ApplyJson(j, r);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{"shotgun", 0}}).find("'shotgun'"), std::string::npos);
  EXPECT_NE(message({{"particles", 2.5}}).find("'particles'"), std::string::npos);
  EXPECT_NE(message({{"prediction", "exact"}}).find("control-noise"), std::string::npos);
  EXPECT_NE(message({{"no_such_key", 1}}).find("'no_such_key'"), std::string::npos);
  EXPECT_NE(message({{"pose_regularisation", {1.0, -1.0, 0.0}}}).find(">= 0"), std::string::npos);
  EXPECT_NE(message(nlohmann::json::array()).find("expected an object"), std::string::npos);
}

TEST(ScPhdSlam, RejectsBadConfiguration) {
  const datasets::Scenario s = SmallScenario(1, 5);
  ScPhdSlamParams p;
  p.shotgun = 0;
  EXPECT_THROW(ScPhdSlam(s.PublicContext(), p, 1), std::invalid_argument);
  p = ScPhdSlamParams();
  EstimatorContext c = s.PublicContext();
  c.control_noise_cov(0, 0) = -1.0;
  EXPECT_THROW(ScPhdSlam(c, p, 1), std::invalid_argument);
  c = s.PublicContext();
  c.motion = nullptr;
  EXPECT_THROW(ScPhdSlam(c, p, 1), std::invalid_argument);
  ScPhdSlam f(s.PublicContext(), p, 1);
  StepData bad;
  bad.times = {0.0, 1.0};
  EXPECT_THROW(f.Step(bad), std::invalid_argument);
}

TEST(UpdateDaughterMap, ParentWeightIsTheSingleClusterLikelihood) {
  const models::SensorModel sensor = PaperSensor();
  const Pose x(0.5, -0.2, 0.05);
  const std::vector<GaussianComponent> components = TwoComponentMap();
  const std::vector<Measurement> z = {Measurement(19.6, 0.06), Measurement(20.9, 0.118)};
  // Both measurements gate with both components, so the example exercises every pair.
  for (int i = 0; i < 2; ++i) {
    for (const Measurement& zj : z) {
      ASSERT_FALSE(std::isnan(HandLogGaussian(x, components[i], zj, sensor.noise_cov, 41.4465)));
    }
  }
  const ScPhdSlamParams params;
  GmPhdMap map;
  map.SetActive(components);
  std::vector<int> ungated;
  const double ll =
      UpdateDaughterMap(map, x, z, sensor, params.map, params.empty_scan_update, &ungated);
  const double hand = HandLogLikelihood(x, components, z, sensor, true);
  EXPECT_NEAR(ll, hand, 1e-9);
  // The missed-detection term is really there: pD (0.8 + 0.6) = 1.33.
  EXPECT_NEAR(HandLogLikelihood(x, components, z, sensor, false) - hand, 0.95 * 1.4, 1e-12);
  // Births from all measurements, as the paper.
  EXPECT_EQ(ungated, (std::vector<int>{0, 1}));

  // An empty scan: weight exp(-sum pD w), detected-area components discounted by 1 - pD.
  GmPhdMap empty_map;
  empty_map.SetActive(components);
  const double ll_empty = UpdateDaughterMap(empty_map, x, {}, sensor, params.map, true, &ungated);
  EXPECT_NEAR(ll_empty, -0.95 * 1.4, 1e-12);
  ASSERT_EQ(empty_map.active().size(), 3u);
  EXPECT_NEAR(empty_map.active()[0].log_weight, std::log(0.8 * 0.05), 1e-12);
  EXPECT_NEAR(empty_map.active()[1].log_weight, std::log(0.6 * 0.05), 1e-12);
  EXPECT_EQ(empty_map.active()[2].log_weight, std::log(0.9));
  // The reference behaviour skips empty scans entirely.
  GmPhdMap skipped;
  skipped.SetActive(components);
  EXPECT_EQ(UpdateDaughterMap(skipped, x, {}, sensor, params.map, false, &ungated), 0.0);
  ExpectSameComponents(skipped.active(), components, "skipped empty scan");
}

TEST(CompareParentWeights, DiffersFromRbPhdByTheMissedDetectionTerm) {
  const models::SensorModel sensor = PaperSensor();
  const std::vector<GaussianComponent> components = TwoComponentMap();
  GmPhdMap map;
  map.SetActive(components);
  // Parent 0 sees both components; parent 1 faces away and sees only the one behind.
  const std::vector<Pose> poses = {Pose(0.5, -0.2, 0.05), Pose(0.0, 0.0, std::numbers::pi),
                                   Pose(0.3, 0.1, 0.04)};
  const std::vector<Measurement> z = {Measurement(19.6, 0.06), Measurement(20.9, 0.118)};
  const auto w = validation::CompareParentWeights(poses, map, z, sensor, phd::MapParams{});
  ASSERT_EQ(w.size(), 3u);
  std::vector<double> sc;
  std::vector<double> rb;
  for (const Pose& x : poses) {
    sc.push_back(HandLogLikelihood(x, components, z, sensor, true));
    rb.push_back(HandLogLikelihood(x, components, z, sensor, false));
  }
  const auto normalise = [](std::vector<double> l) {
    const double m = *std::max_element(l.begin(), l.end());
    double s = 0.0;
    for (double& v : l) s += (v = std::exp(v - m));
    for (double& v : l) v /= s;
    return l;
  };
  const std::vector<double> sc_w = normalise(sc);
  const std::vector<double> rb_w = normalise(rb);
  double sum_sc = 0.0;
  double sum_rb = 0.0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(w[i].single_cluster, sc_w[i], 1e-9) << i;
    EXPECT_NEAR(w[i].rb_phd, rb_w[i], 1e-9) << i;
    EXPECT_NEAR(w[i].log_single_cluster, sc[i], 1e-9) << i;
    EXPECT_NEAR(w[i].log_rb_phd, rb[i], 1e-9) << i;
    sum_sc += w[i].single_cluster;
    sum_rb += w[i].rb_phd;
  }
  EXPECT_NEAR(sum_sc, 1.0, 1e-12);
  EXPECT_NEAR(sum_rb, 1.0, 1e-12);
  // The ratio of parents 0 and 1 changes by exp(-(missed mass 0 - missed mass 1)).
  EXPECT_NEAR(
      std::log(w[0].single_cluster / w[1].single_cluster) - std::log(w[0].rb_phd / w[1].rb_phd),
      -(0.95 * 1.4 - 0.95 * 0.9), 1e-9);
  // The missed-detection mass of each parent: 0.95 times the weight it has in view.
  EXPECT_NEAR(w[0].log_rb_phd - w[0].log_single_cluster, 0.95 * 1.4, 1e-9);
  EXPECT_NEAR(w[1].log_rb_phd - w[1].log_single_cluster, 0.95 * 0.9, 1e-9);
}

TEST(CardinalityMapEstimate, TakesTheRoundedExpectedNumberOfBestComponents) {
  GmPhdMap map;
  map.SetActive({{Landmark(1, 0), Mat2::Identity(), std::log(0.9)},
                 {Landmark(2, 0), Mat2::Identity(), std::log(0.3)}});
  map.SetPassive({{Landmark(3, 0), Mat2::Identity(), std::log(0.8)},
                  {Landmark(4, 0), Mat2::Identity(), std::log(0.1)}});
  std::vector<GaussianComponent> e = CardinalityMapEstimate(map);  // sum 2.1 -> 2
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].mean, Landmark(1, 0));
  EXPECT_EQ(e[1].mean, Landmark(3, 0));
  map.SetPassive({{Landmark(3, 0), Mat2::Identity(), std::log(0.8)},
                  {Landmark(4, 0), Mat2::Identity(), std::log(0.6)}});
  e = CardinalityMapEstimate(map);  // sum 2.6 -> 3
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[2].mean, Landmark(4, 0));
  EXPECT_TRUE(CardinalityMapEstimate(GmPhdMap{}).empty());
}

// With one parent, one child and no process noise, the filter is dead reckoning plus a GM-PHD map
// run with the same births, update and reduction.
TEST(ScPhdSlam, OneParentOneChildIsDeadReckoningPlusAGmPhdMap) {
  const datasets::Scenario s = SmallScenario(4);
  EstimatorContext context = s.PublicContext();
  context.control_noise_cov.setZero();
  ScPhdSlamParams params;
  params.shotgun = 1;
  params.pose_regularisation.setZero();
  ScPhdSlam filter(context, params, 9);
  const models::VelocityMotionModel motion;
  Pose pose = s.initial_pose;
  GmPhdMap map;
  std::vector<Measurement> previous;
  Pose previous_pose = pose;
  std::size_t max_map = 0;
  for (const datasets::ScenarioStep& st : s.steps) {
    ASSERT_FALSE(st.data.measurements.empty());
    if (!previous.empty()) map.AddBirths(previous_pose, previous, s.sensor.noise_cov, params.map);
    for (std::size_t i = 0; i + 1 < st.data.times.size(); ++i) {
      pose = motion.Predict(pose, st.data.controls[i], st.data.times[i + 1] - st.data.times[i]);
    }
    map.Update(pose, st.data.measurements, s.sensor, params.map);
    map.Reduce(pose, s.sensor, params.map);
    previous = st.data.measurements;
    previous_pose = pose;

    const StepOutput out = filter.Step(st.data);
    ASSERT_EQ(out.pose, pose);
    EXPECT_FALSE(out.pose_cov.has_value());
    EXPECT_EQ(out.diag.ess, 1.0);
    EXPECT_FALSE(out.diag.resampled);
    ExpectSameComponents(filter.parents()[0].map.active(), map.active(), "active");
    ExpectSameComponents(filter.parents()[0].map.passive(), map.passive(), "passive");
    EXPECT_EQ(out.diag.map_components, static_cast<int>(map.size()));
    max_map = std::max(max_map, map.size());
  }
  const MapEstimate estimate = filter.Map();
  const std::vector<GaussianComponent> expected = CardinalityMapEstimate(map);
  ASSERT_EQ(estimate.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(estimate.means[i], expected[i].mean);
    EXPECT_EQ(estimate.log_weights[i], expected[i].log_weight);
  }
  EXPECT_GT(max_map, 20u);  // the map is not trivial
  EXPECT_GT(estimate.size(), 10u);
}

// With noise the single child's pose is sampled, and the map is still the GM-PHD map run at the
// filter's own poses.
TEST(ScPhdSlam, OneParentOneChildWithNoiseRunsTheMapAtItsSampledPoses) {
  const datasets::Scenario s = SmallScenario(5, 30);
  ScPhdSlamParams params;
  params.shotgun = 1;
  ScPhdSlam filter(s.PublicContext(), params, 21);
  const models::VelocityMotionModel motion;
  Pose dead_reckoning = s.initial_pose;
  GmPhdMap map;
  std::vector<Measurement> previous;
  Pose previous_pose = s.initial_pose;
  double max_departure = 0.0;
  for (const datasets::ScenarioStep& st : s.steps) {
    const StepOutput out = filter.Step(st.data);
    for (std::size_t i = 0; i + 1 < st.data.times.size(); ++i) {
      dead_reckoning = motion.Predict(dead_reckoning, st.data.controls[i], 1.0);
    }
    max_departure = std::max(max_departure, (out.pose - dead_reckoning).head<2>().norm());
    if (!previous.empty()) map.AddBirths(previous_pose, previous, s.sensor.noise_cov, params.map);
    map.Update(out.pose, st.data.measurements, s.sensor, params.map);
    map.Reduce(out.pose, s.sensor, params.map);
    previous = st.data.measurements;
    previous_pose = out.pose;
    ExpectSameComponents(filter.parents()[0].map.active(), map.active(), "active");
  }
  EXPECT_GT(max_departure, 0.1);  // the pose really is sampled
}

// Every child's log-weight is its parent's plus the single-cluster likelihood at its pose of the
// parent's map with the births added; the N best survive, in child order, normalised.
TEST(ScPhdSlam, ChildWeightsAreSingleClusterLikelihoodsAndPruningKeepsTheBest) {
  const datasets::Scenario s = SmallScenario(6, 25);
  ScPhdSlamParams params;
  params.particles = 3;
  params.shotgun = 4;
  ScPhdSlam filter(s.PublicContext(), params, 33);
  int distinct_parents_seen = 0;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    const StepData& st = s.steps[k].data;
    std::vector<ScParent> before = filter.parents();
    for (ScParent& p : before) {
      if (!p.births.empty()) p.map.AddBirths(p.pose, p.births, s.sensor.noise_cov, params.map);
    }
    filter.Step(st);
    const std::vector<ScChild>& children = filter.last_children();
    const std::size_t copies = k == 0 ? 1 : 4;  // no propagation at the first step
    ASSERT_EQ(children.size(), 3 * copies);
    for (std::size_t c = 0; c < children.size(); ++c) {
      ASSERT_EQ(children[c].parent, static_cast<int>(c / copies));
      GmPhdMap m = before[children[c].parent].map;
      const double ll = UpdateDaughterMap(m, children[c].pose, st.measurements, s.sensor,
                                          params.map, true, nullptr);
      EXPECT_NEAR(children[c].log_weight, before[children[c].parent].log_weight + ll, 1e-9)
          << "step " << k << " child " << c;
    }
    // The kept children are the three highest weights.
    std::vector<double> sorted;
    for (const ScChild& c : children) sorted.push_back(c.log_weight);
    std::sort(sorted.begin(), sorted.end(), std::greater<>());
    std::vector<const ScChild*> kept;
    for (const ScChild& c : children) {
      if (c.kept) kept.push_back(&c);
    }
    ASSERT_EQ(kept.size(), 3u);
    for (const ScChild* c : kept) EXPECT_GE(c->log_weight, sorted[2]);
    double log_total = kNegInf;
    for (const ScChild* c : kept) log_total = LogAddExp(log_total, c->log_weight);
    std::vector<int> parents_of_kept;
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(filter.parents()[i].pose, kept[i]->pose);
      EXPECT_NEAR(filter.parents()[i].log_weight, kept[i]->log_weight - log_total, 1e-12);
      parents_of_kept.push_back(kept[i]->parent);
    }
    std::sort(parents_of_kept.begin(), parents_of_kept.end());
    distinct_parents_seen += static_cast<int>(
        std::unique(parents_of_kept.begin(), parents_of_kept.end()) - parents_of_kept.begin());
  }
  // Pruning is selective: survivors often share a parent.
  EXPECT_LT(distinct_parents_seen, 3 * static_cast<int>(s.steps.size()));
}

TEST(ScPhdSlam, PoseIsTheWeightedMeanAndMapComesFromTheBestParent) {
  const datasets::Scenario s = SmallScenario(7, 30);
  ScPhdSlamParams params;
  params.particles = 5;
  ScPhdSlam filter(s.PublicContext(), params, 44);
  double min_ess = 5.0;
  for (const datasets::ScenarioStep& st : s.steps) {
    const StepOutput out = filter.Step(st.data);
    const auto& parents = filter.parents();
    ASSERT_EQ(parents.size(), 5u);
    Pose mean = Pose::Zero();
    double sum_w = 0.0;
    double sum_w2 = 0.0;
    int best = 0;
    for (std::size_t i = 0; i < parents.size(); ++i) {
      const double w = std::exp(parents[i].log_weight);
      mean += w * parents[i].pose;
      sum_w += w;
      sum_w2 += w * w;
      if (parents[i].log_weight > parents[best].log_weight) best = static_cast<int>(i);
    }
    EXPECT_NEAR(sum_w, 1.0, 1e-12);
    EXPECT_LT((out.pose - mean).norm(), 1e-9);
    ASSERT_TRUE(out.pose_cov.has_value());
    Mat3 spread = Mat3::Zero();
    for (const ScParent& p : parents) {
      spread += std::exp(p.log_weight) * (p.pose - mean) * (p.pose - mean).transpose();
    }
    EXPECT_LT((*out.pose_cov - spread).norm(), 1e-9);
    EXPECT_NEAR(out.diag.ess, 1.0 / sum_w2, 1e-9);
    min_ess = std::min(min_ess, out.diag.ess);
    EXPECT_EQ(filter.best_parent(), best);
    EXPECT_EQ(out.diag.hypotheses, static_cast<int>(filter.last_children().size() / 5));
    const std::vector<GaussianComponent> expected = CardinalityMapEstimate(parents[best].map);
    const MapEstimate map = filter.Map();
    ASSERT_EQ(map.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(map.means[i], expected[i].mean);
  }
  EXPECT_LT(min_ess, 4.99);  // the weights are not uniform
}

TEST(ScPhdSlam, SameSeedSameResultsOtherSeedOtherResults) {
  const datasets::Scenario s = SmallScenario(8, 40);
  ScPhdSlamParams params;
  params.particles = 4;
  const auto run = [&](std::uint64_t seed) {
    ScPhdSlam f(s.PublicContext(), params, seed);
    std::vector<Pose> poses;
    for (const auto& st : s.steps) poses.push_back(f.Step(st.data).pose);
    return std::make_pair(poses, f.Map());
  };
  const auto a = run(5);
  const auto b = run(5);
  const auto c = run(6);
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(a.second.means, b.second.means);
  EXPECT_EQ(a.second.log_weights, b.second.log_weights);
  EXPECT_NE(a.first.back(), c.first.back());
}

// Both samplers draw children whose spread matches the linearised propagated covariance
// Fx Q_n Fx^T + Fu Q_u Fu^T (small noise, so the linearisation is accurate).
TEST(ScPhdSlam, ChildSpreadMatchesThePropagatedCovariance) {
  const models::VelocityMotionModel motion;
  const Pose x0(1.0, 2.0, 0.3);
  const Control u(1.0, 0.05);
  const Mat2 qu = Vec2(0.1 * 0.1, 0.01 * 0.01).asDiagonal();
  const Mat3 qn = Vec3(1e-4, 4e-4, 1e-6).asDiagonal();
  StepData st;
  st.times = {0.0, 1.0};
  st.controls = {u};
  Pose expected_mean = x0;
  Mat3 expected = qn;
  models::PropagatePoseGaussian(motion, qu, st, expected_mean, expected);
  for (ScPredictionSampling mode :
       {ScPredictionSampling::kControlNoise, ScPredictionSampling::kLinearisedGaussian}) {
    EstimatorContext c;
    c.initial_pose = x0;
    c.motion = std::make_shared<models::VelocityMotionModel>();
    c.control_noise_cov = qu;
    ScPhdSlamParams params;
    params.particles = 4000;
    params.shotgun = 1;
    params.pose_regularisation = qn;
    params.prediction = mode;
    ScPhdSlam f(c, params, 77);
    const StepOutput out = f.Step(st);  // no measurements, empty map: equal weights
    ASSERT_TRUE(out.pose_cov.has_value());
    for (int a = 0; a < 3; ++a) {
      const double sd = std::sqrt(expected(a, a));
      EXPECT_NEAR(out.pose(a), expected_mean(a), 4.0 * sd / std::sqrt(4000.0)) << a;
      for (int b = 0; b < 3; ++b) {
        const double scale = std::sqrt(expected(a, a) * expected(b, b));
        EXPECT_NEAR((*out.pose_cov)(a, b), expected(a, b), 0.1 * scale) << a << "," << b;
      }
    }
  }
}

// The Rao-Blackwellised covariance is the mixture of the parents' linearised predicted Gaussians:
// with one parent it is that Gaussian (Fx Q_n Fx^T + Fu Q_u Fu^T over one interval); with several
// equal-weight parents at one pose it is the same Gaussian again.
TEST(ScPhdSlam, RaoBlackwellisedCovarianceIsThePredictedGaussian) {
  const models::VelocityMotionModel motion;
  const Pose x0(1.0, 2.0, 0.3);
  const Control u(1.0, 0.05);
  const Mat2 qu = Vec2(0.1 * 0.1, 0.01 * 0.01).asDiagonal();
  const Mat3 qn = Vec3(1e-4, 4e-4, 1e-6).asDiagonal();
  StepData st;
  st.times = {0.0, 1.0};
  st.controls = {u};
  Pose expected_mean = x0;
  Mat3 expected = qn;
  models::PropagatePoseGaussian(motion, qu, st, expected_mean, expected);
  for (int particles : {1, 5}) {
    EstimatorContext c;
    c.initial_pose = x0;
    c.motion = std::make_shared<models::VelocityMotionModel>();
    c.control_noise_cov = qu;
    ScPhdSlamParams params;
    params.particles = particles;
    params.pose_regularisation = qn;
    ScPhdSlam f(c, params, 5);
    const StepOutput out = f.Step(st);
    ASSERT_TRUE(out.pose_cov_rb.has_value()) << particles;
    ASSERT_TRUE(out.pose_mean_rb.has_value()) << particles;
    EXPECT_TRUE(out.pose_mean_rb->isApprox(expected_mean, 1e-12)) << particles;
    EXPECT_TRUE(out.pose_cov_rb->isApprox(expected, 1e-9)) << particles;
  }
  // A step with one time stamp has no propagation and no Rao-Blackwellised covariance.
  EstimatorContext c;
  c.motion = std::make_shared<models::VelocityMotionModel>();
  ScPhdSlam f(c, ScPhdSlamParams{}, 5);
  StepData still;
  still.times = {0.0};
  EXPECT_FALSE(f.Step(still).pose_cov_rb.has_value());
}

// The NIS is that of the best parent's daughter update: with one parent and one child and no
// noise it is GmPhdMap::Update's at the dead-reckoned pose.
TEST(ScPhdSlam, NisIsTheBestParentsDaughterUpdate) {
  const datasets::Scenario s = SmallScenario(4);
  EstimatorContext context = s.PublicContext();
  context.control_noise_cov.setZero();
  ScPhdSlamParams params;
  params.shotgun = 1;
  params.pose_regularisation.setZero();
  ScPhdSlam filter(context, params, 9);
  const models::VelocityMotionModel motion;
  Pose pose = s.initial_pose;
  GmPhdMap map;
  std::vector<Measurement> previous;
  Pose previous_pose = pose;
  int total = 0;
  for (const datasets::ScenarioStep& st : s.steps) {
    if (!previous.empty()) map.AddBirths(previous_pose, previous, s.sensor.noise_cov, params.map);
    for (std::size_t i = 0; i + 1 < st.data.times.size(); ++i) {
      pose = motion.Predict(pose, st.data.controls[i], st.data.times[i + 1] - st.data.times[i]);
    }
    const phd::PhdUpdateResult update =
        map.Update(pose, st.data.measurements, s.sensor, params.map);
    map.Reduce(pose, s.sensor, params.map);
    previous = st.data.measurements;
    previous_pose = pose;
    const StepOutput out = filter.Step(st.data);
    EXPECT_EQ(out.diag.nis_count, update.nis_count);
    EXPECT_DOUBLE_EQ(out.diag.nis_sum, update.nis_sum);
    total += out.diag.nis_count;
  }
  EXPECT_GT(total, 20);  // landmarks were re-observed
}

}  // namespace
}  // namespace phdslam::filters
