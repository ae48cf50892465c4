#include "validation/runner/studies/parent_weights.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "datasets/scenario_generator.h"

namespace phdslam::validation {
namespace {

datasets::Scenario SmallScenario(std::uint64_t seed) {
  datasets::GeneratorOptions o;
  o.steps = 40;
  o.landmarks = 40;
  o.corridor_half_width = 60.0;
  o.initial_pose = Pose(5.0, -3.0, 0.2);
  return datasets::GenerateScenario(o, seed);
}

// A step of the scenario with measurements (the generator's scans almost always have some).
std::size_t StepWithMeasurements(const datasets::Scenario& s) {
  for (std::size_t k = 20; k < s.steps.size(); ++k) {
    if (!s.steps[k].data.measurements.empty()) return k;
  }
  ADD_FAILURE() << "no scan with measurements";
  return 1;
}

TEST(ParentWeights, BothWeightingsAreNormalisedOverTheSameParents) {
  const datasets::Scenario s = SmallScenario(3);
  ParentWeightsSettings settings;
  settings.step = StepWithMeasurements(s);
  settings.parents = 400;
  settings.stream_seed = 11;
  const ParentWeights w = CompareParentWeightingAtStep(s, settings);
  ASSERT_EQ(w.poses.size(), 400u);
  ASSERT_EQ(w.single_cluster.size(), 400u);
  ASSERT_EQ(w.rb_phd.size(), 400u);
  EXPECT_NEAR(std::accumulate(w.single_cluster.begin(), w.single_cluster.end(), 0.0), 1.0, 1e-9);
  EXPECT_NEAR(std::accumulate(w.rb_phd.begin(), w.rb_phd.end(), 0.0), 1.0, 1e-9);
  EXPECT_EQ(w.measurements, s.steps[settings.step].data.measurements.size());
  EXPECT_GT(w.map_components, 0u);
  ASSERT_TRUE(w.true_pose);
  // The parents are draws from the predicted Gaussian: their mean lies within 4 standard errors
  // of its mean in x and y.
  Vec3 mean = Vec3::Zero();
  for (const Pose& p : w.poses) mean += p;
  mean /= 400.0;
  for (int i = 0; i < 2; ++i) {
    const double se = std::sqrt(w.predicted_cov(i, i) / 400.0);
    EXPECT_NEAR(mean(i), w.predicted_mean(i), 4.0 * se + 1e-9) << "coordinate " << i;
  }
  // The previous best parent moved by one control step.
  EXPECT_GT((w.predicted_mean - w.previous_pose).head<2>().norm(), 0.0);
}

TEST(ParentWeights, AWideSpreadChangesTheMissedDetectionMassBetweenParents) {
  // Parents spread over tens of metres and degrees see different parts of the map: their
  // missed-detection masses differ, and the single-cluster weights differ from the RB-PHD ones
  // by exactly that term: log w_sc - log w_rb = -missed mass + a constant.
  const datasets::Scenario s = SmallScenario(3);
  ParentWeightsSettings settings;
  settings.step = StepWithMeasurements(s);
  settings.parents = 200;
  settings.spread = 30.0;
  const ParentWeights w = CompareParentWeightingAtStep(s, settings);
  const auto [lo, hi] = std::minmax_element(w.missed_mass.begin(), w.missed_mass.end());
  EXPECT_GE(*lo, 0.0);
  EXPECT_GT(*hi - *lo, 0.5);
  const double offset = (w.log_single_cluster[0] - w.log_rb_phd[0]) + w.missed_mass[0];
  for (std::size_t i = 1; i < w.poses.size(); ++i) {
    EXPECT_NEAR((w.log_single_cluster[i] - w.log_rb_phd[i]) + w.missed_mass[i], offset, 1e-9);
  }
}

TEST(ParentWeights, IsReplayableFromItsSeed) {
  const datasets::Scenario s = SmallScenario(4);
  ParentWeightsSettings settings;
  settings.step = StepWithMeasurements(s);
  settings.parents = 50;
  settings.stream_seed = 5;
  const ParentWeights a = CompareParentWeightingAtStep(s, settings);
  const ParentWeights b = CompareParentWeightingAtStep(s, settings);
  EXPECT_EQ(ParentWeightsCsv(a), ParentWeightsCsv(b));
  settings.stream_seed = 6;
  EXPECT_NE(ParentWeightsCsv(a), ParentWeightsCsv(CompareParentWeightingAtStep(s, settings)));
}

TEST(ParentWeights, WritesOneRowPerParentAndTheSettingsAsJson) {
  const datasets::Scenario s = SmallScenario(5);
  ParentWeightsSettings settings;
  settings.step = StepWithMeasurements(s);
  settings.parents = 7;
  const ParentWeights w = CompareParentWeightingAtStep(s, settings);
  const std::string csv = ParentWeightsCsv(w);
  EXPECT_EQ(csv.rfind("parent,x,y,theta,sc_weight,rb_weight,sc_log_weight,rb_log_weight,"
                      "missed_mass,sf_weight,sf_log_weight\n",
                      0),
            0u);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 8);
  const nlohmann::json j = ParentWeightsJson(w);
  EXPECT_EQ(j.at("step").get<std::size_t>(), settings.step);
  EXPECT_EQ(j.at("parents").get<int>(), 7);
  EXPECT_EQ(j.at("true_pose").size(), 3u);
  EXPECT_GE(j.at("ess_single_cluster").get<double>(), 1.0 - 1e-9);
  EXPECT_LE(j.at("ess_rb_phd").get<double>(), 7.0 + 1e-9);
  EXPECT_GE(j.at("ess_single_feature").get<double>(), 1.0 - 1e-9);
  EXPECT_LE(j.at("ess_single_feature").get<double>(), 7.0 + 1e-9);
}

TEST(ParentWeights, SingleFeatureWeightsAreNormalisedAndDifferFromTheOthers) {
  const datasets::Scenario s = SmallScenario(3);
  ParentWeightsSettings settings;
  settings.step = StepWithMeasurements(s);
  settings.parents = 200;
  settings.spread = 10.0;
  const ParentWeights w = CompareParentWeightingAtStep(s, settings);
  ASSERT_EQ(w.single_feature.size(), 200u);
  EXPECT_NEAR(std::accumulate(w.single_feature.begin(), w.single_feature.end(), 0.0), 1.0, 1e-9);
  double largest_gap = 0.0;
  for (std::size_t i = 0; i < w.poses.size(); ++i) {
    ASSERT_TRUE(std::isfinite(w.log_single_feature[i]));
    largest_gap = std::max(largest_gap, std::abs(w.single_feature[i] - w.rb_phd[i]));
  }
  EXPECT_GT(largest_gap, 1e-3);
}

TEST(ParentWeights, OverStepsGivesOneRowPerStepWithMeasurementsAndPairedTests) {
  const datasets::Scenario s = SmallScenario(6);
  ParentWeightsSettings settings;
  settings.parents = 20;
  settings.stream_seed = 2;
  const std::vector<std::size_t> steps = {5, 10, 15, 20, 25, 30, 35};
  const std::vector<StepEss> rows = CompareParentWeightingOverSteps(s, settings, steps);
  std::size_t with_measurements = 0;
  for (std::size_t k : steps) with_measurements += !s.steps[k].data.measurements.empty();
  ASSERT_EQ(rows.size(), with_measurements);
  double sum_sf = 0.0;
  for (const StepEss& r : rows) {
    EXPECT_EQ(r.measurements, s.steps[r.step].data.measurements.size());
    for (double ess : {r.single_cluster, r.rb_phd, r.single_feature}) {
      EXPECT_GE(ess, 1.0 - 1e-9);
      EXPECT_LE(ess, 20.0 + 1e-9);
    }
    sum_sf += r.single_feature;
  }
  const nlohmann::json j = StepEssJson(rows);
  EXPECT_NEAR(j.at("mean_ess_single_feature").get<double>(), sum_sf / rows.size(), 1e-12);
  EXPECT_EQ(j.at("single_cluster_minus_single_feature").at("n").get<std::size_t>(), rows.size());
  const std::string csv = StepEssCsv(rows);
  EXPECT_EQ(csv.rfind("step,measurements,map_components,ess_single_cluster,ess_rb_phd,"
                      "ess_single_feature\n",
                      0),
            0u);
  EXPECT_EQ(StepEssCsv(CompareParentWeightingOverSteps(s, settings, steps)), csv);
  EXPECT_THROW(CompareParentWeightingOverSteps(s, settings, {10, 5}), std::invalid_argument);
}

TEST(ParentWeights, RejectsStepsWithoutAScanAndTooFewParents) {
  datasets::Scenario s = SmallScenario(6);
  ParentWeightsSettings settings;
  settings.step = 0;
  EXPECT_THROW(CompareParentWeightingAtStep(s, settings), std::invalid_argument);
  settings.step = s.steps.size();
  EXPECT_THROW(CompareParentWeightingAtStep(s, settings), std::invalid_argument);
  settings.step = 10;
  s.steps[10].data.measurements.clear();
  s.steps[10].origin.clear();
  try {
    CompareParentWeightingAtStep(s, settings);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("step 10 has no measurements"), std::string::npos);
  }
  settings.step = StepWithMeasurements(s);
  settings.parents = 1;
  EXPECT_THROW(CompareParentWeightingAtStep(s, settings), std::invalid_argument);
  settings.parents = 10;
  settings.spread = 0.0;
  EXPECT_THROW(CompareParentWeightingAtStep(s, settings), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::validation
