#include "validation/runner/results/summary.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/test_temp_dir.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"

namespace phdslam::validation {
namespace {

constexpr const char* kSummaryHeader =
    "estimator,particles,runs,steps,pos_rmse_m,heading_rmse_deg,gospa_mean_m,gospa_std_m,"
    "ess_pct,resampling_pct,ms_per_step_mean,";

// A metrics.json written out by hand: run "a" N=1 seed 1, position errors {1, 2, 3} m,
// heading errors {1, -1, 2} deg, GOSPA 30 m, ESS 50 %, resampling 1/3, 1.5 ms per step.
constexpr const char* kHandWrittenRun = R"({
  "estimator": "a", "particles": 1, "seed": 1, "stream_seed": 99,
  "steps": 3,
  "pos_rmse_m": 2.160246899, "pos_err_std_m": 1.0,
  "pos_err_count": 3, "pos_err_sum_m": 6.0, "pos_err_sq_sum_m2": 14.0,
  "heading_rmse_deg": 1.414213562, "heading_err_std_deg": 1.527525232,
  "heading_err_count": 3, "heading_err_sum_deg": 2.0, "heading_err_sq_sum_deg2": 6.0,
  "gospa_m": 30.0, "gospa_localisation_mp": 300.0, "gospa_missed_mp": 400.0,
  "gospa_false_mp": 200.0, "n_missed": 2, "n_false": 1, "gospa_c": 20.0, "gospa_p": 2.0,
  "map_size": 12, "truth_map_size": 10,
  "ess_pct": 50.0, "resampling_pct": 33.33333333333333, "hypotheses_mean": 2.0,
  "map_components_mean": 8.0,
  "pose_nees_mean": 3.0, "pose_nees_count": 2, "pose_nees_sum": 6.0,
  "landmark_nees_mean": 2.0, "landmark_nees_count": 5, "landmark_nees_sum": 10.0,
  "gps_matched_steps": null,
  "ms_per_step_mean": 1.5, "ms_per_step_std": 0.5, "ms_count": 3, "ms_sum": 4.5,
  "ms_sq_sum": 7.25, "ms_total": 4.5
})";

void WriteJson(const std::filesystem::path& out, const std::string& estimator, int particles,
               std::uint64_t seed, const std::string& file, const std::string& text) {
  const auto folder = RunFolder(out, estimator, particles, seed);
  std::filesystem::create_directories(folder);
  WriteFileAtomically(folder / file, text);
}

nlohmann::json Identity(const std::string& estimator, int particles, std::uint64_t seed) {
  return {{"estimator", estimator}, {"particles", particles}, {"seed", seed}};
}

// Run "a" N=1 seed 2: one step with position error 4 m, heading error 3 deg, GOSPA 40 m,
// ESS 100 %, no resampling, 2.5 ms.
RunMetrics SecondRun() {
  RunMetrics m;
  m.steps = 1;
  m.position_m.Add(4.0);
  m.heading_deg.Add(3.0);
  m.gospa = FinalMapGospa{40.0, 400.0, 800.0, 400.0, 4, 2};
  m.map_size = 8;
  m.truth_map_size = 10;
  m.ess_pct = 100.0;
  m.resampling_pct = 0.0;
  m.hypotheses_mean = 6.0;
  m.map_components_mean = 4.0;
  m.pose_nees.Add(5.0);
  m.step_ms.Add(2.5);
  m.total_ms = 2.5;
  AssociationCounts da;
  da.tp = 9;
  da.fn = 1;
  da.tn = 3;
  da.fp = 1;
  m.association = da;
  m.solver_iterations = 12;
  m.solver_converged = false;
  m.relocalisations = 3;
  m.neg_log_posterior = 1234.5;
  return m;
}

std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// The cells of `csv` as header name -> value for data row `row` (0-based).
std::map<std::string, std::string> Row(const std::string& csv, int row) {
  std::stringstream in(csv);
  std::string header;
  std::getline(in, header);
  std::string line;
  for (int i = 0; i <= row; ++i) std::getline(in, line);
  const auto names = SplitCsvLine(header);
  const auto values = SplitCsvLine(line);
  EXPECT_EQ(names.size(), values.size()) << line;
  std::map<std::string, std::string> cells;
  for (std::size_t i = 0; i < names.size() && i < values.size(); ++i) cells[names[i]] = values[i];
  return cells;
}

class SummaryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    out_ = datasets::testing::FreshTestDir();
    WriteJson(out_, "a", 1, 1, kMetricsFile, kHandWrittenRun);
    nlohmann::json second = Identity("a", 1, 2);
    second.update(ToJson(SecondRun()));
    WriteJson(out_, "a", 1, 2, kMetricsFile, second.dump());
    // Group "b" N=10: one finished run without truth (GPS data) and one failed run.
    RunMetrics gps;
    gps.steps = 2;
    gps.position_m.Add(5.0);
    gps.gps_matched_steps = 1;
    gps.map_size = 3;
    gps.ess_pct = 40.0;
    gps.resampling_pct = 50.0;
    nlohmann::json third = Identity("b", 10, 1);
    third.update(ToJson(gps));
    WriteJson(out_, "b", 10, 1, kMetricsFile, third.dump());
    nlohmann::json failed = Identity("b", 10, 2);
    failed["error"] = "boom";
    WriteJson(out_, "b", 10, 2, kErrorFile, failed.dump());
    // A run in progress (no metrics.json, no error.json) is ignored.
    std::filesystem::create_directories(RunFolder(out_, "b", 10, 3));
  }
  std::filesystem::path out_;
};

TEST_F(SummaryTest, ReadsFinishedAndFailedRuns) {
  const ResultsInventory inv = ReadResults(out_);
  ASSERT_EQ(inv.runs.size(), 3u);
  EXPECT_EQ(inv.runs[0].estimator, "a");
  EXPECT_EQ(inv.runs[0].seed, 1u);
  EXPECT_EQ(inv.runs[1].seed, 2u);
  EXPECT_EQ(inv.runs[2].estimator, "b");
  ASSERT_EQ(inv.failed.size(), 1u);
  EXPECT_EQ(inv.failed[0].seed, 2u);
  EXPECT_EQ(inv.failed[0].error, "boom");
}

TEST_F(SummaryTest, PoolsErrorsOverAllStepsOfAllRuns) {
  const std::vector<GroupSummary> groups = SummariseGroups(ReadResults(out_));
  ASSERT_EQ(groups.size(), 2u);
  const GroupSummary& a = groups[0];
  EXPECT_EQ(a.estimator, "a");
  EXPECT_EQ(a.runs, 2u);
  EXPECT_EQ(a.failed_runs, 0u);
  // Pooled over the four steps {1, 2, 3, 4}: sqrt(30 / 4); sample std sqrt(5 / 3).
  EXPECT_DOUBLE_EQ(*a.position_m.Rms(), std::sqrt(7.5));
  EXPECT_DOUBLE_EQ(*a.position_m.Std(), std::sqrt(5.0 / 3.0));
  // Not the mean of the per-run RMSEs (2.1602 and 4).
  EXPECT_GT(std::abs(*a.position_m.Rms() - 0.5 * (std::sqrt(14.0 / 3.0) + 4.0)), 0.3);
  // Headings {1, -1, 2, 3}: sqrt(15 / 4).
  EXPECT_DOUBLE_EQ(*a.heading_deg.Rms(), std::sqrt(15.0 / 4.0));
  EXPECT_DOUBLE_EQ(*a.gospa_m.Mean(), 35.0);
  EXPECT_DOUBLE_EQ(*a.gospa_m.Std(), std::sqrt(50.0));
  // ESS and resampling weighted by steps: (3 * 50 + 1 * 100) / 4 and (3 * 33.3 + 0) / 4.
  EXPECT_DOUBLE_EQ(*a.ess_pct, 62.5);
  EXPECT_NEAR(*a.resampling_pct, 25.0, 1e-12);
  EXPECT_DOUBLE_EQ(*a.hypotheses_mean, (3 * 2.0 + 6.0) / 4.0);
  EXPECT_DOUBLE_EQ(*a.pose_nees.Mean(), 11.0 / 3.0);
  EXPECT_DOUBLE_EQ(*a.step_ms.Mean(), 7.0 / 4.0);
  EXPECT_DOUBLE_EQ(*a.steps, 2.0);
  const GroupSummary& b = groups[1];
  EXPECT_EQ(b.estimator, "b");
  EXPECT_EQ(b.particles, 10);
  EXPECT_EQ(b.runs, 1u);
  EXPECT_EQ(b.failed_runs, 1u);
  EXPECT_DOUBLE_EQ(*b.position_m.Rms(), 5.0);
  EXPECT_FALSE(b.heading_deg.Rms());
  EXPECT_EQ(b.gospa_m.count, 0u);
}

TEST_F(SummaryTest, WritesSummaryAndRunsCsv) {
  WriteSummaryFiles(out_);
  const std::string summary = ReadTextFile(out_ / kSummaryFile);
  EXPECT_EQ(summary.rfind(kSummaryHeader, 0), 0u) << summary;
  auto a = Row(summary, 0);
  EXPECT_EQ(a["estimator"], "a");
  EXPECT_EQ(a["particles"], "1");
  EXPECT_EQ(a["runs"], "2");
  EXPECT_EQ(a["steps"], "2");
  EXPECT_EQ(a["pos_rmse_m"], FormatNumber(std::sqrt(7.5)));
  EXPECT_EQ(a["pos_rmse_m"], "2.738612788");
  EXPECT_EQ(a["gospa_mean_m"], "35");
  EXPECT_EQ(a["gospa_std_m"], "7.071067812");
  EXPECT_EQ(a["gospa_sem_m"], "5");
  EXPECT_EQ(a["ess_pct"], "62.5");
  EXPECT_EQ(a["n_missed_mean"], "3");
  EXPECT_EQ(a["n_false_mean"], "1.5");
  EXPECT_EQ(a["gospa_missed_mean_mp"], "600");
  EXPECT_EQ(a["map_size_mean"], "10");
  EXPECT_EQ(a["failed_runs"], "0");
  EXPECT_EQ(a["ms_per_step_mean"], "1.75");
  // Association rates pool the counts of the scored runs (the hand-written run has none).
  EXPECT_EQ(a["da_tpr"], "0.9");
  EXPECT_EQ(a["da_tnr"], "0.75");
  EXPECT_EQ(a["da_positives"], "10");
  EXPECT_EQ(a["da_negatives"], "4");
  // Solver iterations: the one run that has them.
  EXPECT_EQ(a["solver_iterations_mean"], "12");
  // ... and its final solve did not converge: counted, not hidden.
  EXPECT_EQ(a["solver_unconverged_runs"], "1");
  auto b = Row(summary, 1);
  EXPECT_EQ(b["solver_unconverged_runs"], "");
  EXPECT_EQ(b["da_tpr"], "");
  EXPECT_EQ(b["da_positives"], "");
  EXPECT_EQ(b["estimator"], "b");
  EXPECT_EQ(b["failed_runs"], "1");
  EXPECT_EQ(b["gospa_mean_m"], "");
  EXPECT_EQ(b["heading_rmse_deg"], "");
  EXPECT_EQ(b["pos_rmse_m"], "5");

  const std::string runs = ReadTextFile(out_ / kRunsTableFile);
  EXPECT_EQ(runs.rfind("estimator,particles,seed,steps,pos_rmse_m,heading_rmse_deg,gospa_m,", 0),
            0u)
      << runs;
  auto r1 = Row(runs, 0);
  EXPECT_EQ(r1["seed"], "1");
  EXPECT_EQ(r1["pos_rmse_m"], FormatNumber(std::sqrt(14.0 / 3.0)));
  EXPECT_EQ(r1["gospa_m"], "30");
  EXPECT_EQ(r1["n_false"], "1");
  EXPECT_EQ(r1["gospa_localisation_mp"], "300");
  EXPECT_EQ(r1["da_tpr"], "");
  EXPECT_EQ(Row(runs, 1)["da_tnr"], "0.75");
  EXPECT_EQ(Row(runs, 1)["solver_iterations"], "12");
  EXPECT_EQ(r1["solver_iterations"], "");
  EXPECT_EQ(Row(runs, 1)["solver_converged"], "0");
  EXPECT_EQ(r1["solver_converged"], "");
  EXPECT_EQ(Row(runs, 1)["relocalisations"], "3");
  EXPECT_EQ(r1["relocalisations"], "");
  EXPECT_EQ(Row(runs, 1)["neg_log_posterior"], "1234.5");
  EXPECT_EQ(r1["neg_log_posterior"], "");
  auto r3 = Row(runs, 2);
  EXPECT_EQ(r3["estimator"], "b");
  EXPECT_EQ(r3["gospa_m"], "");
  EXPECT_EQ(r3["truth_map_size"], "");

  const std::string table = FormatSummaryTable(SummariseGroups(ReadResults(out_)));
  EXPECT_NE(table.find("2.739"), std::string::npos) << table;
  EXPECT_NE(table.find("35.00 (7.07)"), std::string::npos) << table;
}

TEST_F(SummaryTest, AnOverflowedErrorInAnOldMetricsFileCountsAsAFailedRun) {
  nlohmann::json poisoned = Identity("a", 1, 3);
  poisoned.update(ToJson(SecondRun()));
  poisoned.erase(kFormatVersionKey);        // written before the key existed (version 1)
  poisoned["pos_err_sq_sum_m2"] = nullptr;  // what an overflowed sum was written as
  WriteJson(out_, "a", 1, 3, kMetricsFile, poisoned.dump());
  const ResultsInventory inv = ReadResults(out_);
  EXPECT_EQ(inv.runs.size(), 3u);
  ASSERT_EQ(inv.failed.size(), 2u);
  EXPECT_EQ(inv.failed[0].estimator, "a");
  EXPECT_EQ(inv.failed[0].seed, 3u);
  EXPECT_NE(inv.failed[0].error.find("pos_err_sq_sum_m2"), std::string::npos);
  const std::vector<GroupSummary> groups = WriteSummaryFiles(out_);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].failed_runs, 1u);
  EXPECT_TRUE(std::filesystem::exists(out_ / "summary.csv"));
}

TEST_F(SummaryTest, AMetricsFileOfAnUnknownFormatVersionIsRefusedNamingTheFile) {
  nlohmann::json newer = Identity("a", 1, 3);
  newer.update(ToJson(SecondRun()));
  newer[kFormatVersionKey] = kMetricsFormatVersion + 1;
  WriteJson(out_, "a", 1, 3, kMetricsFile, newer.dump());
  try {
    ReadResults(out_);
    ADD_FAILURE() << "a metrics.json of an unknown version was read";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("seed-3/metrics.json"), std::string::npos) << what;
    EXPECT_NE(what.find("format_version " + std::to_string(kMetricsFormatVersion + 1)),
              std::string::npos)
        << what;
  }
}

TEST(RunMetricsCheck, NonFiniteErrorsAreNamedAndFiniteOnesPass) {
  RunMetrics m;
  m.position_m.Add(1.0);
  m.heading_deg.Add(2.0);
  EXPECT_EQ(NonFiniteMetrics(m), "");
  m.position_m.Add(1e200);  // its square overflows
  EXPECT_NE(NonFiniteMetrics(m).find("position error is not finite"), std::string::npos);
  RunMetrics h;
  h.heading_deg.Add(std::numeric_limits<double>::infinity());
  EXPECT_NE(NonFiniteMetrics(h).find("heading error"), std::string::npos);
}

TEST_F(SummaryTest, ReportsACorruptFile) {
  WriteJson(out_, "a", 1, 3, kMetricsFile, "{\"estimator\": \"a\", \"particles\": 1}");
  try {
    ReadResults(out_);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("seed-3"), std::string::npos) << e.what();
  }
  WriteJson(out_, "a", 1, 3, kMetricsFile, "not json");
  EXPECT_THROW(ReadResults(out_), std::runtime_error);
}

TEST(SummariseGroupNees, AveragesOverRunsAtStepsWhereEveryRunHasANees) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  // Steps 0 and 2 lack a NEES in some run; step 5 exists in the first run only.
  const std::vector<double> r1 = {kNaN, 3.0, 6.0, 1.0, 20.0, 4.0};
  const std::vector<double> r2 = {kNaN, 3.0, kNaN, 2.0, 20.0};
  const std::optional<GroupNees> g = SummariseGroupNees({&r1, &r2});
  ASSERT_TRUE(g.has_value());
  EXPECT_EQ(g->steps, 3u);  // steps 1, 3, 4: run averages 3, 1.5, 20
  EXPECT_DOUBLE_EQ(g->mean, (3.0 + 1.5 + 20.0) / 3.0);
  // chi-square_6 quantiles 0.025 and 0.975, divided by 2 runs (scipy.stats.chi2.ppf).
  EXPECT_NEAR(g->lower, 0.6186721228956014, 1e-9);
  EXPECT_NEAR(g->upper, 7.22468766772396, 1e-9);
  EXPECT_DOUBLE_EQ(g->fraction_inside, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(g->median, 3.0);

  const std::vector<double> none = {kNaN, kNaN};
  EXPECT_FALSE(SummariseGroupNees({&r1, &none}).has_value());
  EXPECT_FALSE(SummariseGroupNees({}).has_value());
  const std::vector<double> empty;
  EXPECT_FALSE(SummariseGroupNees({&r1, &empty}).has_value());
}

TEST(SummariseGroupNis, PoolsTheMeasurementsOfEveryRunPerStep) {
  // Step 0 has no measurement; step 1: 4 / 2 measurements; step 2 (first run only): 30 / 1.
  const std::vector<double> s1 = {0.0, 2.0, 30.0};
  const std::vector<double> c1 = {0.0, 1.0, 1.0};
  const std::vector<double> s2 = {0.0, 2.0};
  const std::vector<double> c2 = {0.0, 1.0};
  const std::optional<GroupNis> g = SummariseGroupNis({&s1, &s2}, {&c1, &c2});
  ASSERT_TRUE(g.has_value());
  EXPECT_EQ(g->steps, 2u);
  EXPECT_DOUBLE_EQ(g->mean, 34.0 / 3.0);
  EXPECT_DOUBLE_EQ(g->median, 16.0);  // of 2 and 30
  // Step 1: 2 inside [chi2_4(0.025), chi2_4(0.975)] / 2 = [0.242, 5.572]; step 2: 30 above
  // chi2_2(0.975) = 7.378.
  EXPECT_DOUBLE_EQ(g->fraction_inside, 0.5);
  const std::vector<double> zero = {0.0, 0.0};
  EXPECT_FALSE(SummariseGroupNis({&zero}, {&zero}).has_value());
}

TEST(Summary, NeesColumnsComeFromTheStepsFiles) {
  const auto out = datasets::testing::FreshTestDir();
  // Two runs of "p" N=5, three steps; the first step has no covariance. NEES: run 1 {4, 2},
  // run 2 {2, 2}.
  const char* steps[] = {"step,x,nees\n0,0,\n1,0,4\n2,0,2\n", "step,x,nees\n0,0,\n1,0,2\n2,0,2\n"};
  for (std::uint64_t seed : {1, 2}) {
    RunMetrics m;
    m.steps = 3;
    m.pose_nees.Add(seed == 1 ? 4.0 : 2.0);
    m.pose_nees.Add(2.0);
    nlohmann::json j = Identity("p", 5, seed);
    j.update(ToJson(m));
    WriteJson(out, "p", 5, seed, kMetricsFile, j.dump());
    WriteJson(out, "p", 5, seed, kStepsFile, steps[seed - 1]);
  }
  const ResultsInventory inventory = ReadResults(out);
  ASSERT_EQ(inventory.runs.size(), 2u);
  ASSERT_EQ(inventory.runs[0].step_nees.size(), 3u);
  EXPECT_TRUE(std::isnan(inventory.runs[0].step_nees[0]));
  EXPECT_EQ(inventory.runs[0].step_nees[1], 4.0);
  WriteSummaryFiles(out);
  auto row = Row(ReadTextFile(out / kSummaryFile), 0);
  EXPECT_EQ(row["pose_nees_mean"], "2.5");
  EXPECT_EQ(row["nees_mean"], "2.5");  // run averages 3 and 2
  EXPECT_NEAR(std::stod(row["nees_lower_95"]), 0.6186721228956014, 1e-8);
  EXPECT_NEAR(std::stod(row["nees_upper_95"]), 7.22468766772396, 1e-8);
  EXPECT_EQ(row["nees_fraction_inside"], "1");
  EXPECT_EQ(row["nees_steps"], "2");
}

TEST_F(SummaryTest, NeesColumnsAreEmptyWithoutStepNees) {
  WriteSummaryFiles(out_);
  auto a = Row(ReadTextFile(out_ / kSummaryFile), 0);
  EXPECT_EQ(a["pose_nees_mean"], FormatNumber(11.0 / 3.0));
  ASSERT_TRUE(a.contains("nees_mean"));
  EXPECT_EQ(a["nees_mean"], "");
  EXPECT_EQ(a["nees_fraction_inside"], "");
}

TEST(Summary, EmptyFolderGivesHeaderOnly) {
  const auto out = datasets::testing::FreshTestDir();
  const auto groups = WriteSummaryFiles(out);
  EXPECT_TRUE(groups.empty());
  const std::string summary = ReadTextFile(out / kSummaryFile);
  EXPECT_EQ(summary.rfind(kSummaryHeader, 0), 0u);
  EXPECT_EQ(std::count(summary.begin(), summary.end(), '\n'), 1);
}

}  // namespace
}  // namespace phdslam::validation
