#include "validation/runner/evaluation/run_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "datasets/map_io.h"
#include "datasets/test_temp_dir.h"
#include "validation/runner/execution/run_estimator.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/results/run_files.h"

namespace phdslam::validation {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Three steps at t = 0, 1, 2 with true poses along the x axis and two true landmarks.
datasets::Scenario TruthScenario() {
  datasets::Scenario s;
  s.name = "hand";
  s.seed = 4;
  for (int k = 0; k < 3; ++k) {
    datasets::ScenarioStep step;
    step.data.times =
        k == 0 ? std::vector<double>{0.0} : std::vector<double>{k - 1.0, static_cast<double>(k)};
    if (k > 0) step.data.controls = {Control(1.0, 0.0)};
    s.steps.push_back(step);
    s.truth.poses.push_back(Pose(k, 0.0, 0.0));
  }
  s.truth.landmarks = {Landmark(0.0, 0.0), Landmark(10.0, 0.0)};
  return s;
}

// Estimates off by (0, 0), (3, 4) m and 0.1 rad, (0, 1) m; ESS 4, 2, 1 of N = 4.
RunRecord HandRecord() {
  RunRecord r;
  r.estimator = "hand";
  r.particles = 4;
  r.seed = 4;
  r.step_times = {0.0, 1.0, 2.0};
  r.poses = {Pose(0.0, 0.0, 0.0), Pose(4.0, 4.0, 0.1), Pose(2.0, 1.0, 0.0)};
  r.pose_covs = {std::nullopt, Mat3::Identity(), Mat3::Zero()};
  filters::StepDiagnostics d;
  d.ess = 4.0;
  d.hypotheses = 1;
  d.map_components = 2;
  r.diagnostics.push_back(d);
  d.ess = 2.0;
  d.resampled = true;
  d.hypotheses = 2;
  d.map_components = 4;
  r.diagnostics.push_back(d);
  d.ess = 1.0;
  d.resampled = false;
  d.hypotheses = 3;
  d.map_components = 6;
  r.diagnostics.push_back(d);
  r.step_ms = {1.0, 2.0, 3.0};
  r.total_ms = 6.0;
  r.final_map.means = {Landmark(0.0, 3.0)};
  r.final_map.covs = {Mat2::Identity()};
  r.final_map.log_weights = {0.0};
  return r;
}

// A deterministic estimator has no particle weights: its ESS and resampling rate are left
// empty (as a bound's are), while its other step diagnostics are still averaged.
TEST(EvaluateRun, LeavesEssAndResamplingEmptyWithoutParticleWeights) {
  RunRecord record = HandRecord();
  record.particle_weights = false;
  const RunMetrics m = EvaluateRun(record, TruthScenario()).metrics;
  EXPECT_FALSE(m.ess_pct);
  EXPECT_FALSE(m.resampling_pct);
  EXPECT_DOUBLE_EQ(*m.hypotheses_mean, 2.0);
}

TEST(EvaluateRun, ComputesEveryMetricAsByHand) {
  const RunEvaluation ev = EvaluateRun(HandRecord(), TruthScenario());
  const RunMetrics& m = ev.metrics;
  EXPECT_EQ(m.steps, 3u);
  ASSERT_EQ(ev.position_error_m.size(), 3u);
  EXPECT_DOUBLE_EQ(ev.position_error_m[1], 5.0);
  EXPECT_DOUBLE_EQ(ev.position_error_m[2], 1.0);
  EXPECT_DOUBLE_EQ(*m.position_m.Rms(), std::sqrt((0.0 + 25.0 + 1.0) / 3.0));
  EXPECT_NEAR(ev.heading_error_deg[1], 0.1 * kDeg, 1e-12);
  EXPECT_NEAR(*m.heading_deg.Rms(), std::sqrt(0.01 / 3.0) * kDeg, 1e-12);
  // GOSPA (c = 20, p = 2): (0,3) is assigned to (0,0) at 3 m, (10,0) is missed: 9 + 200.
  ASSERT_TRUE(m.gospa);
  EXPECT_DOUBLE_EQ(m.gospa->gospa, std::sqrt(209.0));
  EXPECT_DOUBLE_EQ(m.gospa->localisation, 9.0);
  EXPECT_DOUBLE_EQ(m.gospa->missed, 200.0);
  EXPECT_DOUBLE_EQ(m.gospa->false_, 0.0);
  EXPECT_EQ(m.gospa->n_missed, 1);
  EXPECT_EQ(m.gospa->n_false, 0);
  EXPECT_EQ(m.map_size, 1u);
  EXPECT_EQ(*m.truth_map_size, 2u);
  // Landmark NEES of the one pair with identity covariance: 3^2.
  EXPECT_EQ(m.landmark_nees.count, 1u);
  EXPECT_DOUBLE_EQ(*m.landmark_nees.Mean(), 9.0);
  // ESS/N = 1, 0.5, 0.25; resampled at one step of three.
  EXPECT_DOUBLE_EQ(*m.ess_pct, 100.0 * 1.75 / 3.0);
  EXPECT_DOUBLE_EQ(*m.resampling_pct, 100.0 / 3.0);
  EXPECT_DOUBLE_EQ(*m.hypotheses_mean, 2.0);
  EXPECT_DOUBLE_EQ(*m.map_components_mean, 4.0);
  // Pose NEES only where the covariance is positive definite (step 1): 9 + 16 + 0.01.
  EXPECT_EQ(m.pose_nees.count, 1u);
  EXPECT_NEAR(*m.pose_nees.Mean(), 25.01, 1e-12);
  // Per step: none without a covariance (step 0) or with a zero one (step 2).
  ASSERT_EQ(ev.pose_nees.size(), 3u);
  EXPECT_TRUE(std::isnan(ev.pose_nees[0]));
  EXPECT_NEAR(ev.pose_nees[1], 25.01, 1e-12);
  EXPECT_TRUE(std::isnan(ev.pose_nees[2]));
  EXPECT_DOUBLE_EQ(*m.step_ms.Mean(), 2.0);
  EXPECT_DOUBLE_EQ(m.total_ms, 6.0);
  EXPECT_FALSE(m.gps_matched_steps);
}

TEST(EvaluateRun, LeavesStepsWithoutTruthOutOfThePoseMetrics) {
  datasets::Scenario scenario = TruthScenario();
  scenario.truth.pose_scored = {true, false, true};  // step 1 lies in a truth gap
  RunRecord record = HandRecord();
  record.pose_covs = {std::nullopt, Mat3::Identity(), Mat3::Identity()};
  const RunEvaluation ev = EvaluateRun(record, scenario);
  const RunMetrics& m = ev.metrics;
  EXPECT_TRUE(std::isnan(ev.position_error_m[1]));
  EXPECT_TRUE(std::isnan(ev.heading_error_deg[1]));
  EXPECT_TRUE(std::isnan(ev.pose_nees[1]));
  EXPECT_EQ(m.position_m.count, 2u);
  EXPECT_DOUBLE_EQ(*m.position_m.Rms(), std::sqrt((0.0 + 1.0) / 2.0));
  EXPECT_EQ(m.pose_nees.count, 1u);  // step 2 only: (0, 1, 0) with identity covariance
  EXPECT_NEAR(*m.pose_nees.Mean(), 1.0, 1e-12);
  // The map is scored as without the mask.
  ASSERT_TRUE(m.gospa);
  EXPECT_DOUBLE_EQ(m.gospa->gospa, std::sqrt(209.0));
  // steps.csv leaves the true pose of the unscored step empty.
  const std::string csv = StepsCsv(record, scenario, ev);
  EXPECT_NE(csv.find("\n1,1,4,4,0.1,,,,,,"), std::string::npos) << csv;
}

TEST(EvaluateRun, GpsOnlyScenarioScoresAgainstGps) {
  datasets::Scenario s = TruthScenario();
  s.truth.poses.clear();
  s.truth.landmarks.clear();
  // Fixes near t = 0 (10 ms off) and t = 2 (40 ms off: outside the 25 ms window).
  s.truth.gps = {{0.01, Vec2(0.0, 2.0)}, {2.04, Vec2(2.0, 1.0)}};
  RunRecord r = HandRecord();
  r.diagnostics.clear();
  const RunEvaluation ev = EvaluateRun(r, s);
  EXPECT_EQ(*ev.metrics.gps_matched_steps, 1u);
  EXPECT_DOUBLE_EQ(ev.position_error_m[0], 2.0);
  EXPECT_TRUE(std::isnan(ev.position_error_m[1]));
  EXPECT_TRUE(std::isnan(ev.position_error_m[2]));
  EXPECT_DOUBLE_EQ(*ev.metrics.position_m.Rms(), 2.0);
  EXPECT_EQ(ev.metrics.heading_deg.count, 0u);
  EXPECT_FALSE(ev.metrics.gospa);
  EXPECT_FALSE(ev.metrics.truth_map_size);
  EXPECT_FALSE(ev.metrics.ess_pct);
  EXPECT_EQ(ev.metrics.pose_nees.count, 0u);
}

// Measurements with origin labels at steps 1 and 2: landmark 0 twice (first sighting, then a
// re-observation), clutter twice, landmark 1 once (first sighting).
datasets::Scenario LabelledScenario() {
  datasets::Scenario s = TruthScenario();
  s.steps[1].data.measurements = {Measurement(1.0, 0.0), Measurement(5.0, 1.0)};
  s.steps[1].origin = {0, datasets::kClutter};
  s.steps[2].data.measurements = {Measurement(2.0, 0.0), Measurement(8.0, 0.0),
                                  Measurement(7.0, -1.0)};
  s.steps[2].origin = {0, 1, datasets::kClutter};
  return s;
}

TEST(EvaluateRun, ScoresTheReportedAssociationAgainstTheOriginLabels) {
  const Landmark none(kNaN, kNaN);
  RunRecord r = HandRecord();
  // Step 1: landmark 0 is new (a first sighting), the clutter is left alone (TN). Step 2:
  // landmark 0 associated with a component near it (TP), landmark 1 new, the clutter explained
  // by landmark 1's component (FP).
  r.associations = {{}, {none, none}, {Landmark(0.5, 0.0), none, Landmark(9.0, 0.0)}};
  const RunMetrics m = EvaluateRun(r, LabelledScenario()).metrics;
  ASSERT_TRUE(m.association);
  EXPECT_EQ(m.association->tp, 1);
  EXPECT_EQ(m.association->fn, 0);
  EXPECT_EQ(m.association->tn, 1);
  EXPECT_EQ(m.association->fp, 1);
  EXPECT_EQ(m.association->first_sightings, 2);
  EXPECT_DOUBLE_EQ(m.association->tpr(), 1.0);
  EXPECT_DOUBLE_EQ(m.association->tnr(), 0.5);

  // The component nearest to landmark 1 counts as a wrong association for landmark 0: FN.
  r.associations[2][0] = Landmark(9.5, 0.0);
  EXPECT_EQ(EvaluateRun(r, LabelledScenario()).metrics.association->fn, 1);

  // An association vector of the wrong length names the step.
  r.associations[2].pop_back();
  try {
    (void)EvaluateRun(r, LabelledScenario());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("step 2"), std::string::npos) << e.what();
  }
}

TEST(EvaluateRun, LeavesTheAssociationUnscoredWithoutLabelsOrAssociations) {
  // Batch estimators record no associations.
  EXPECT_FALSE(EvaluateRun(HandRecord(), LabelledScenario()).metrics.association);
  // Real data: measurements of unknown origin.
  RunRecord r = HandRecord();
  r.associations = {{}, {}, {}};
  datasets::Scenario s = LabelledScenario();
  s.steps[2].origin[2] = datasets::kUnknownOrigin;
  EXPECT_FALSE(EvaluateRun(r, s).metrics.association);
  // An estimator that never associates: scored, every measurement unreported, no rates.
  const RunMetrics m = EvaluateRun(r, LabelledScenario()).metrics;
  ASSERT_TRUE(m.association);
  EXPECT_EQ(m.association->unreported, 5);
  EXPECT_TRUE(std::isnan(m.association->tpr()));
}

TEST(EvaluateRun, LeavesOutANeesThatOverflows) {
  // Positive definite by the Cholesky test, but e'P^-1 e overflows to infinity: that step has no
  // NEES, and the sufficient statistics stay finite (metrics.json would otherwise hold null).
  RunRecord r = HandRecord();
  r.pose_covs[1] = Mat3::Identity() * 1e-320;
  const RunEvaluation ev = EvaluateRun(r, TruthScenario());
  EXPECT_TRUE(std::isnan(ev.pose_nees[1]));
  EXPECT_EQ(ev.metrics.pose_nees.count, 0u);
  EXPECT_TRUE(std::isfinite(ev.metrics.pose_nees.sum));

  // Finite values whose sum overflows: written as null, read back as +infinity.
  RunMetrics m = ev.metrics;
  m.pose_nees.Add(1e308);
  m.pose_nees.Add(1e308);
  const nlohmann::json j = nlohmann::json::parse(ToJson(m).dump());  // as written to the file
  EXPECT_TRUE(j.at("pose_nees_sum").is_null());
  const RunMetrics back = RunMetricsFromJson(j, "test");
  EXPECT_EQ(back.pose_nees.count, 2u);
  EXPECT_TRUE(std::isinf(back.pose_nees.sum));
}

TEST(EvaluateRun, RejectsARecordOfTheWrongLength) {
  RunRecord r = HandRecord();
  r.poses.pop_back();
  EXPECT_THROW(EvaluateRun(r, TruthScenario()), std::invalid_argument);
}

TEST(RunMetricsJson, RoundTripsTheSufficientStatistics) {
  const RunMetrics m = EvaluateRun(HandRecord(), TruthScenario()).metrics;
  const nlohmann::json j = ToJson(m);
  EXPECT_TRUE(j.at("gps_matched_steps").is_null());
  EXPECT_DOUBLE_EQ(j.at("pos_rmse_m").get<double>(), *m.position_m.Rms());
  const RunMetrics back = RunMetricsFromJson(nlohmann::json::parse(j.dump()), "test");
  EXPECT_EQ(back.position_m.count, m.position_m.count);
  EXPECT_EQ(back.position_m.sum, m.position_m.sum);
  EXPECT_EQ(back.position_m.sum_sq, m.position_m.sum_sq);
  EXPECT_EQ(back.heading_deg.sum_sq, m.heading_deg.sum_sq);
  EXPECT_EQ(back.gospa->gospa, m.gospa->gospa);
  EXPECT_EQ(back.gospa->n_missed, 1);
  EXPECT_EQ(*back.ess_pct, *m.ess_pct);
  EXPECT_EQ(back.pose_nees.sum, m.pose_nees.sum);
  EXPECT_EQ(back.step_ms.sum_sq, m.step_ms.sum_sq);
  EXPECT_EQ(ToJson(back), j);
  EXPECT_TRUE(j.at("da_tpr").is_null());
  EXPECT_TRUE(j.at("da_tp").is_null());
  EXPECT_FALSE(back.association);

  // Association counts round-trip; files written before they existed read as unscored.
  RunRecord labelled = HandRecord();
  labelled.associations = {{},
                           {Landmark(kNaN, kNaN), Landmark(kNaN, kNaN)},
                           {Landmark(0.0, 0.0), Landmark(kNaN, kNaN), Landmark(kNaN, kNaN)}};
  const nlohmann::json da = ToJson(EvaluateRun(labelled, LabelledScenario()).metrics);
  EXPECT_EQ(da.at("da_tp").get<long>(), 1);
  EXPECT_DOUBLE_EQ(da.at("da_tnr").get<double>(), 1.0);
  const RunMetrics da_back = RunMetricsFromJson(nlohmann::json::parse(da.dump()), "test");
  ASSERT_TRUE(da_back.association);
  EXPECT_EQ(da_back.association->tn, 2);
  EXPECT_EQ(ToJson(da_back), da);
  // A file written before format_version existed (version 1) may lack the later keys.
  nlohmann::json old = j;
  old.erase("format_version");
  for (const char* key : {"da_tp", "da_fn", "da_tn", "da_fp", "da_first_sightings",
                          "da_first_sightings_associated", "da_unreported", "da_tpr", "da_tnr"}) {
    old.erase(key);
  }
  EXPECT_FALSE(RunMetricsFromJson(old, "test").association);
  // Online estimators have no solver iterations; files written before the key existed neither.
  EXPECT_TRUE(j.at("solver_iterations").is_null());
  old.erase("solver_iterations");
  EXPECT_FALSE(RunMetricsFromJson(old, "test").solver_iterations);
  EXPECT_TRUE(j.at("solver_converged").is_null());
  old.erase("solver_converged");
  EXPECT_FALSE(RunMetricsFromJson(old, "test").solver_converged);
  // Estimators that do not re-localise have no count; files of versions 1 and 2 lack the key.
  EXPECT_TRUE(j.at("relocalisations").is_null());
  old.erase("relocalisations");
  EXPECT_FALSE(RunMetricsFromJson(old, "test").relocalisations);
  nlohmann::json v2 = j;
  v2["format_version"] = 2;
  v2.erase("relocalisations");
  v2.erase("neg_log_posterior");
  EXPECT_FALSE(RunMetricsFromJson(v2, "test").relocalisations);
  // Estimators that do not score their solution have no posterior; files of versions 1-3 lack it.
  EXPECT_TRUE(j.at("neg_log_posterior").is_null());
  nlohmann::json v3 = j;
  v3["format_version"] = 3;
  v3.erase("neg_log_posterior");
  EXPECT_FALSE(RunMetricsFromJson(v3, "test").neg_log_posterior);

  nlohmann::json missing = j;
  missing.erase("pos_err_count");
  EXPECT_THROW(RunMetricsFromJson(missing, "test"), std::runtime_error);
  // Version 2 requires the keys version 1 could lack, version 3 those version 2 could lack,
  // version 4 those version 3 could lack.
  nlohmann::json without_counts = j;
  without_counts.erase("da_tp");
  EXPECT_THROW(RunMetricsFromJson(without_counts, "test"), std::runtime_error);
  without_counts["format_version"] = 2;
  EXPECT_THROW(RunMetricsFromJson(without_counts, "test"), std::runtime_error);
  nlohmann::json without_relocalisations = j;
  without_relocalisations.erase("relocalisations");
  EXPECT_THROW(RunMetricsFromJson(without_relocalisations, "test"), std::runtime_error);
  nlohmann::json without_posterior = j;
  without_posterior.erase("neg_log_posterior");
  EXPECT_THROW(RunMetricsFromJson(without_posterior, "test"), std::runtime_error);
  nlohmann::json mistyped = j;
  mistyped["ms_sum"] = "fast";
  EXPECT_THROW(RunMetricsFromJson(mistyped, "test"), std::runtime_error);
}

// The message of the std::runtime_error `read` throws, or "" when it throws none.
template <typename Read>
std::string ErrorOf(Read read) {
  try {
    read();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(RunMetricsJson, WritesItsFormatVersionAndRefusesUnknownOnes) {
  const nlohmann::json j = ToJson(EvaluateRun(HandRecord(), TruthScenario()).metrics);
  EXPECT_EQ(j.at("format_version"), kMetricsFormatVersion);
  EXPECT_EQ(MetricsFormatVersion(j, "a/metrics.json"), 4);

  // A file without the key is version 1 and reads as the same metrics.
  nlohmann::json v1 = j;
  v1.erase("format_version");
  EXPECT_EQ(MetricsFormatVersion(v1, "a/metrics.json"), 1);
  EXPECT_EQ(ToJson(RunMetricsFromJson(v1, "a/metrics.json")), j);

  nlohmann::json newer = j;
  newer["format_version"] = 5;
  const std::string why = ErrorOf([&] { RunMetricsFromJson(newer, "runs/x/metrics.json"); });
  EXPECT_NE(why.find("runs/x/metrics.json"), std::string::npos) << why;
  EXPECT_NE(why.find("format_version 5"), std::string::npos) << why;
  for (const nlohmann::json& bad :
       {nlohmann::json(0), nlohmann::json("2"), nlohmann::json(2.5), nlohmann::json(nullptr)}) {
    nlohmann::json mistyped = j;
    mistyped["format_version"] = bad;
    const std::string message = ErrorOf([&] { RunMetricsFromJson(mistyped, "b/metrics.json"); });
    EXPECT_NE(message.find("b/metrics.json"), std::string::npos) << bad.dump();
    EXPECT_NE(message.find("format_version"), std::string::npos) << bad.dump();
  }
  // Only version-1 files can hold the nulls older versions wrote for an overflowed error.
  nlohmann::json overflowed = v1;
  overflowed["pos_err_sum_m"] = nullptr;
  EXPECT_EQ(OverflowedMetricsField(overflowed), "pos_err_sum_m");
  overflowed["format_version"] = 2;
  EXPECT_EQ(OverflowedMetricsField(overflowed), "");
  EXPECT_THROW(RunMetricsFromJson(overflowed, "c/metrics.json"), std::runtime_error);
}

// A batch estimator returning fixed poses, for RunEstimator.
class FixedBatch final : public datasets::BatchEstimator {
 public:
  explicit FixedBatch(std::size_t poses) : poses_(poses) {}
  datasets::BatchResult Solve(const datasets::Scenario&) override {
    datasets::BatchResult r;
    r.poses.assign(poses_, Pose(1.0, 2.0, 3.0));
    r.map.means = {Landmark(5.0, 5.0)};
    r.iterations = 17;
    r.converged = false;
    r.relocalisations = 2;
    r.neg_log_posterior = -12.5;
    return r;
  }

 private:
  std::size_t poses_;
};

TEST(RunEstimator, RecordsBatchResultsAndChecksTheirLength) {
  const datasets::Scenario s = TruthScenario();
  EstimatorEntry entry;
  entry.name = "fixed";
  entry.batch = true;
  std::size_t poses = 3;
  entry.make_batch = [&](const EstimatorRequest&) { return std::make_unique<FixedBatch>(poses); };
  EstimatorRequest request;
  std::size_t reported = 0;
  const RunRecord r = RunEstimator(entry, request, s, [&](std::size_t n) { reported += n; });
  EXPECT_EQ(reported, 3u);
  EXPECT_EQ(r.poses.size(), 3u);
  EXPECT_TRUE(r.diagnostics.empty());
  EXPECT_TRUE(r.step_ms.empty());
  EXPECT_EQ(r.step_times, (std::vector<double>{0.0, 1.0, 2.0}));
  EXPECT_EQ(r.final_map.size(), 1u);
  const RunEvaluation ev = EvaluateRun(r, s);
  EXPECT_FALSE(ev.metrics.ess_pct);
  EXPECT_EQ(ev.metrics.step_ms.count, 0u);
  ASSERT_TRUE(ev.metrics.solver_iterations);
  EXPECT_EQ(*ev.metrics.solver_iterations, 17u);
  const nlohmann::json j = ToJson(ev.metrics);
  EXPECT_EQ(j.at("solver_iterations").get<int>(), 17);
  EXPECT_EQ(*RunMetricsFromJson(j, "test").solver_iterations, 17u);
  // A solve that did not converge is reported, not silently used.
  ASSERT_TRUE(ev.metrics.solver_converged);
  EXPECT_FALSE(*ev.metrics.solver_converged);
  EXPECT_FALSE(j.at("solver_converged").get<bool>());
  EXPECT_EQ(RunMetricsFromJson(j, "test").solver_converged, std::optional<bool>(false));
  // A batch estimator's re-localisations reach the metrics.
  ASSERT_TRUE(ev.metrics.relocalisations);
  EXPECT_EQ(*ev.metrics.relocalisations, 2u);
  EXPECT_EQ(j.at("relocalisations").get<int>(), 2);
  EXPECT_EQ(RunMetricsFromJson(j, "test").relocalisations, std::optional<std::size_t>(2));
  // And its score.
  EXPECT_EQ(ev.metrics.neg_log_posterior, std::optional<double>(-12.5));
  EXPECT_EQ(j.at("neg_log_posterior").get<double>(), -12.5);
  EXPECT_EQ(RunMetricsFromJson(j, "test").neg_log_posterior, std::optional<double>(-12.5));
  nlohmann::json mistyped = j;
  mistyped["solver_converged"] = "yes";
  EXPECT_THROW(RunMetricsFromJson(mistyped, "test"), std::runtime_error);
  poses = 2;
  EXPECT_THROW(RunEstimator(entry, request, s), std::runtime_error);
}

TEST(StepsCsv, HasANeesColumnEmptyWhereThereIsNone) {
  const datasets::Scenario s = TruthScenario();
  const RunRecord r = HandRecord();
  const std::string csv = StepsCsv(r, s, EvaluateRun(r, s));
  const CsvTable table = ParseCsv(csv, "steps.csv");
  const std::optional<std::size_t> nees = table.FindColumn("nees");
  ASSERT_TRUE(nees);
  ASSERT_EQ(*nees, 15u);  // the existing columns keep their places; new ones follow
  ASSERT_EQ(table.rows.size(), 3u);
  EXPECT_EQ(table.rows[0][*nees], "");
  EXPECT_EQ(table.rows[1][*nees], "25.01");
  EXPECT_EQ(table.rows[2][*nees], "");
}

TEST(StepsCsv, LeavesEssAndResampledEmptyForADeterministicEstimator) {
  const datasets::Scenario s = TruthScenario();
  RunRecord r = HandRecord();
  const auto cells = [&](const RunRecord& record) {
    const CsvTable table = ParseCsv(StepsCsv(record, s, EvaluateRun(record, s)), "steps.csv");
    const std::size_t ess = *table.FindColumn("ess");
    const std::size_t resampled = *table.FindColumn("resampled");
    return std::pair{table.rows[1][ess], table.rows[1][resampled]};
  };
  EXPECT_NE(cells(r).first, "");
  EXPECT_NE(cells(r).second, "");
  r.particle_weights = false;
  EXPECT_EQ(cells(r).first, "");
  EXPECT_EQ(cells(r).second, "");
}

TEST(StepsCsv, HasRbNeesAndNisColumnsAndMetricsRoundTrip) {
  const datasets::Scenario s = TruthScenario();
  RunRecord r = HandRecord();
  r.pose_means_rb = {std::nullopt, Pose(4.0, 4.0, 0.1), Pose(2.0, 1.0, 0.0)};
  r.pose_covs_rb = {std::nullopt, Mat3(2.0 * Mat3::Identity()), Mat3::Zero()};
  r.diagnostics[1].nis_sum = 3.0;
  r.diagnostics[1].nis_count = 2;
  const RunEvaluation ev = EvaluateRun(r, s);
  const CsvTable table = ParseCsv(StepsCsv(r, s, ev), "steps.csv");
  const auto column = [&](const std::string& name) {
    const std::optional<std::size_t> c = table.FindColumn(name);
    EXPECT_TRUE(c) << name;
    return c.value_or(0);
  };
  EXPECT_EQ(table.rows[0][column("nees_rb")], "");
  EXPECT_EQ(table.rows[1][column("nees_rb")], "12.505");  // the identity case halved
  EXPECT_EQ(table.rows[2][column("nees_rb")], "");
  EXPECT_EQ(table.rows[0][column("nis_sum")], "");
  EXPECT_EQ(table.rows[1][column("nis_sum")], "3");
  EXPECT_EQ(table.rows[1][column("nis_count")], "2");
  EXPECT_EQ(table.rows[1][column("gps_nees_rb")], "");
  // 12.505 > chi-square_3(0.95) = 7.81: outside the ellipsoid; 25.01 too.
  EXPECT_EQ(ev.metrics.pose_nees_rb.count, 1u);
  EXPECT_EQ(ev.metrics.pose_coverage_rb_inside, 0u);
  EXPECT_EQ(ev.metrics.pose_coverage_inside, 0u);
  EXPECT_EQ(ev.metrics.nis_count, 2u);
  EXPECT_EQ(ev.metrics.nis_sum, 3.0);
  const RunMetrics back = RunMetricsFromJson(ToJson(ev.metrics), "test");
  EXPECT_EQ(back.pose_nees_rb.count, 1u);
  EXPECT_EQ(back.pose_nees_rb.sum, ev.metrics.pose_nees_rb.sum);
  EXPECT_NEAR(back.pose_nees_rb.sum, 12.505, 1e-12);
  EXPECT_EQ(back.nis_count, 2u);
  EXPECT_EQ(back.nis_sum, 3.0);
}

TEST(RunFiles, WritesACovarianceThatIsNotFiniteAsNotAvailable) {
  const datasets::Scenario s = TruthScenario();
  RunRecord r = HandRecord();
  r.final_map.means.push_back(Landmark(10.0, 1.0));
  r.final_map.log_weights.push_back(0.0);
  r.final_map.covs.push_back(Mat2::Constant(kNaN));
  const std::filesystem::path folder = datasets::testing::FreshTestDir();
  WriteRunFiles(folder, r, s, EvaluateRun(r, s), nlohmann::json{{"estimator", "hand"}});
  const std::vector<datasets::MapPoint> map = datasets::ReadMapCsv(folder / "map.csv");
  ASSERT_EQ(map.size(), 2u);
  ASSERT_TRUE(map[0].cov);
  EXPECT_EQ((*map[0].cov)(0, 0), 1.0);
  EXPECT_FALSE(map[1].cov);
}

TEST(ParticlesCsv, NormalisesTheLogWeightsOfEachStep) {
  RunRecord r;
  EXPECT_EQ(ParticlesCsv(r), "");
  r.particle_states = {{{Pose(1.0, 2.0, 0.0), std::log(3.0)}, {Pose(3.0, 4.0, 0.0), std::log(1.0)}},
                       {{Pose(5.0, 6.0, 0.0), -1000.0}}};
  EXPECT_EQ(ParticlesCsv(r),
            "step,particle,x,y,log_weight\n"
            "0,0,1,2," +
                FormatNumber(std::log(0.75)) +
                "\n"
                "0,1,3,4," +
                FormatNumber(std::log(0.25)) +
                "\n"
                "1,0,5,6,0\n");
}

// An online estimator with two particles whose poses are the step count and its negative.
class TwoParticles final : public filters::OnlineEstimator {
 public:
  filters::StepOutput Step(const datasets::StepData&) override {
    ++steps_;
    return {};
  }
  [[nodiscard]] filters::MapEstimate Map() const override { return {}; }
  [[nodiscard]] std::vector<std::pair<Pose, double>> ParticleStates() const override {
    return {{Pose(steps_, 0.0, 0.0), 0.0}, {Pose(-steps_, 0.0, 0.0), -1.0}};
  }

 private:
  int steps_ = 0;
};

TEST(RunEstimator, RecordsParticlesOnlyWhenAsked) {
  const datasets::Scenario s = TruthScenario();
  EstimatorEntry entry;
  entry.name = "two";
  entry.make_online = [](const EstimatorRequest&) { return std::make_unique<TwoParticles>(); };
  const EstimatorRequest request{"two", 2, 0, s.name, {}, nullptr};
  EXPECT_TRUE(RunEstimator(entry, request, s).particle_states.empty());
  const RunRecord r = RunEstimator(entry, request, s, {}, true);
  ASSERT_EQ(r.particle_states.size(), 3u);
  ASSERT_EQ(r.particle_states[2].size(), 2u);
  EXPECT_EQ(r.particle_states[2][1].first(0), -3.0);
  EXPECT_EQ(r.particle_states[2][1].second, -1.0);
  // An estimator without particles records none.
  const filters::EstimatorContext context = s.PublicContext();
  EXPECT_TRUE(RunEstimator(FindEstimator("odometry"),
                           EstimatorRequest{"odometry", 1, 0, s.name, {}, &context}, s, {}, true)
                  .particle_states.empty());
}

// The run of a deterministic estimator (dead reckoning: --particles 1 only) records no particle
// weights, so its ESS and resampling rate stay empty; that of a particle filter records them.
TEST(RunEstimator, RecordsParticleWeightsOnlyForParticleFilters) {
  const datasets::Scenario s = TruthScenario();
  const filters::EstimatorContext context = s.PublicContext();
  const RunRecord odometry = RunEstimator(
      FindEstimator("odometry"), EstimatorRequest{"odometry", 1, 0, s.name, {}, &context}, s);
  EXPECT_FALSE(odometry.particle_weights);
  EXPECT_FALSE(EvaluateRun(odometry, s).metrics.ess_pct);
  EXPECT_FALSE(EvaluateRun(odometry, s).metrics.resampling_pct);
  EstimatorEntry entry;
  entry.name = "two";
  entry.make_online = [](const EstimatorRequest&) { return std::make_unique<TwoParticles>(); };
  const RunRecord two = RunEstimator(entry, EstimatorRequest{"two", 2, 0, s.name, {}, nullptr}, s);
  EXPECT_TRUE(two.particle_weights);
  EXPECT_TRUE(EvaluateRun(two, s).metrics.ess_pct);
}

TEST(RunEstimator, StepsAnOnlineEstimatorAndTimesEachStep) {
  const datasets::Scenario s = TruthScenario();
  const filters::EstimatorContext context = s.PublicContext();
  const RunRecord r = RunEstimator(FindEstimator("odometry"),
                                   EstimatorRequest{"odometry", 1, 0, s.name, {}, &context}, s);
  ASSERT_EQ(r.poses.size(), 3u);
  EXPECT_NEAR(r.poses[2](0), 2.0, 1e-12);  // 1 m/s straight for two steps
  EXPECT_EQ(r.diagnostics.size(), 3u);
  ASSERT_EQ(r.step_ms.size(), 3u);
  double sum = 0.0;
  for (double ms : r.step_ms) {
    EXPECT_GE(ms, 0.0);
    sum += ms;
  }
  EXPECT_DOUBLE_EQ(r.total_ms, sum);
}

// A bound's record (pcrb): its poses are the truth and its covariances the bound; the error
// columns hold the root of the position block's trace and of the heading entry, the RMSE columns
// the roots of their means, and nothing an estimate would have (GOSPA, NEES).
TEST(EvaluateRun, ABoundPutsTheBoundWhereAnEstimatorHasItsError) {
  const datasets::Scenario s = TruthScenario();
  RunRecord r;
  r.estimator = "pcrb";
  r.bound = true;
  r.seed = 4;
  r.step_times = {0.0, 1.0, 2.0};
  r.poses = s.truth.poses;
  r.pose_covs = {Mat3::Zero(), Vec3(1.0, 3.0, 0.01).asDiagonal().toDenseMatrix(),
                 Vec3(4.0, 5.0, 0.04).asDiagonal().toDenseMatrix()};
  r.final_map.means = s.truth.landmarks;
  r.final_map.covs = {Mat2::Identity(), Mat2::Identity()};
  r.final_map.log_weights = {0.0, 0.0};
  const RunEvaluation ev = EvaluateRun(r, s);
  EXPECT_DOUBLE_EQ(ev.position_error_m[0], 0.0);
  EXPECT_DOUBLE_EQ(ev.position_error_m[1], 2.0);
  EXPECT_DOUBLE_EQ(ev.position_error_m[2], 3.0);
  EXPECT_NEAR(ev.heading_error_deg[2], 0.2 * kDeg, 1e-12);
  EXPECT_NEAR(*ev.metrics.position_m.Rms(), std::sqrt((0.0 + 4.0 + 9.0) / 3.0), 1e-12);
  EXPECT_NEAR(*ev.metrics.heading_deg.Rms(), std::sqrt((0.0 + 0.01 + 0.04) / 3.0) * kDeg, 1e-12);
  EXPECT_FALSE(ev.metrics.gospa.has_value());
  EXPECT_EQ(ev.metrics.pose_nees.count, 0U);
  EXPECT_TRUE(std::isnan(ev.pose_nees[1]));
  EXPECT_EQ(ev.metrics.map_size, 2U);
}

}  // namespace
}  // namespace phdslam::validation
