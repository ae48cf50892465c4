// The batch smoother's re-localisations through the runner: counted in metrics.json and
// runs.csv (`relocalisations`) when the own association's incremental pass can re-localise,
// empty where it cannot.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "datasets/test_temp_dir.h"
#include "validation/runner/execution/monte_carlo.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/testing/results_testing.h"

namespace phdslam::validation {
namespace {

namespace fs = std::filesystem;

// The paper's scenario over 100 steps with a small odometry noise, diag(0.1 m/s, 0.01 rad/s)^2:
// with incremental_relocalisation_std 0.5 m the incremental pass enters the re-localisation mode
// and matches its scans with the map (three times on seed 1; under a second per run).
MonteCarloPlan SmootherPlan(nlohmann::json overrides) {
  MonteCarloPlan plan;
  ScenarioOptions options;
  options.steps = 100;
  options.settings = {{"control_noise_cov", {0.01, 0.0001}}};
  plan.scenario = MakeScenarioSource("paper-synthetic", options);
  plan.estimators = {{FindEstimator("smoother-unknown"), std::move(overrides)}};
  plan.particles = {1};
  plan.seeds = {1};
  return plan;
}

MonteCarloSettings QuietRun(const fs::path& out) {
  MonteCarloSettings s;
  s.out = out;
  s.jobs = 1;
  s.show_progress = false;
  s.report_failures = false;
  return s;
}

// The one row of runs.csv, by column name.
std::map<std::string, std::string> OnlyRunsRow(const fs::path& out) {
  std::stringstream text(ReadTextFile(out / kRunsTableFile));
  std::string header;
  std::string row;
  std::getline(text, header);
  std::getline(text, row);
  const std::vector<std::string> names = testing::SplitCells(header);
  const std::vector<std::string> cells = testing::SplitCells(row);
  EXPECT_EQ(names.size(), cells.size()) << row;
  std::map<std::string, std::string> by_name;
  for (std::size_t i = 0; i < names.size() && i < cells.size(); ++i) by_name[names[i]] = cells[i];
  return by_name;
}

nlohmann::json RunAndReadMetrics(const fs::path& out, nlohmann::json overrides) {
  const MonteCarloReport report = RunMonteCarlo(SmootherPlan(std::move(overrides)), QuietRun(out));
  EXPECT_EQ(report.finished, 1u);
  return nlohmann::json::parse(
      ReadTextFile(RunFolder(out, "smoother-unknown", 1, 1) / kMetricsFile));
}

TEST(SmootherRelocalisationRuns, ReLocalisationsAreCountedInTheRunsResults) {
  const fs::path out = datasets::testing::FreshTestDir();
  const nlohmann::json metrics = RunAndReadMetrics(
      out, {{"initialisation", "incremental"}, {"incremental_relocalisation_std", 0.5}});
  ASSERT_TRUE(metrics.at("relocalisations").is_number_integer()) << metrics.dump();
  const int count = metrics.at("relocalisations").get<int>();
  EXPECT_GT(count, 0);
  EXPECT_EQ(OnlyRunsRow(out).at("relocalisations"), std::to_string(count));
}

TEST(SmootherRelocalisationRuns, EmptyWhereTheSmootherCannotReLocalise) {
  // The incremental pass with re-localisation off, and the sequential pass (the default
  // initialisation: batch), which has no re-localisation at all.
  for (const nlohmann::json& overrides :
       {nlohmann::json{{"initialisation", "incremental"}}, nlohmann::json::object()}) {
    const fs::path out = datasets::testing::FreshTestDir();
    const nlohmann::json metrics = RunAndReadMetrics(out, overrides);
    EXPECT_TRUE(metrics.at("relocalisations").is_null()) << overrides.dump();
    EXPECT_EQ(OnlyRunsRow(out).at("relocalisations"), "") << overrides.dump();
  }
}

}  // namespace
}  // namespace phdslam::validation
