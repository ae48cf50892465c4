// The fixed-lag smoother (window-known, window) through the runner: a solve that does not
// converge is counted in the run's metrics, and a window longer than the run is a failed run
// whose error names window_length, never a silent result.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "datasets/test_temp_dir.h"
#include "validation/runner/execution/monte_carlo.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"

namespace phdslam::validation {
namespace {

namespace fs = std::filesystem;

constexpr int kSteps = 30;

MonteCarloPlan WindowPlan(const std::string& estimator, nlohmann::json overrides) {
  MonteCarloPlan plan;
  ScenarioOptions options;
  options.steps = kSteps;
  plan.scenario = MakeScenarioSource("paper-synthetic", options);
  plan.estimators = {{FindEstimator(estimator), std::move(overrides)}};
  plan.particles = {1};
  plan.seeds = {1};
  return plan;
}

MonteCarloSettings Quiet(const fs::path& out) {
  MonteCarloSettings s;
  s.out = out;
  s.jobs = 1;
  s.show_progress = false;
  s.report_failures = false;
  return s;
}

TEST(WindowEstimatorRuns, UnconvergedSolvesAreCountedInTheRunsMetrics) {
  for (const std::string name : {"window-known", "window"}) {
    const fs::path out = datasets::testing::FreshTestDir();
    // One iteration per solve and an unreachable tolerance: every solve stops at the limit.
    const MonteCarloReport report = RunMonteCarlo(
        WindowPlan(name, {{"max_iterations", 1}, {"function_tolerance", 1e-300}}), Quiet(out));
    ASSERT_EQ(report.finished, 1u) << name;
    const nlohmann::json metrics =
        nlohmann::json::parse(ReadTextFile(RunFolder(out, name, 1, 1) / kMetricsFile));
    // Step 0 is the known initial pose; every later step adds a pose and is solved.
    EXPECT_GE(metrics.at("solves").get<int>(), kSteps - 1) << name;
    EXPECT_GT(metrics.at("unconverged_solves").get<int>(), 0) << name;
    EXPECT_LE(metrics.at("unconverged_solves").get<int>(), metrics.at("solves").get<int>());
    EXPECT_NE(ReadTextFile(out / kRunsTableFile).find("unconverged_solves"), std::string::npos);
  }
}

TEST(WindowEstimatorRuns, DefaultSettingsConverge) {
  const fs::path out = datasets::testing::FreshTestDir();
  const MonteCarloReport report =
      RunMonteCarlo(WindowPlan("window-known", nlohmann::json::object()), Quiet(out));
  ASSERT_EQ(report.finished, 1u);
  const nlohmann::json metrics =
      nlohmann::json::parse(ReadTextFile(RunFolder(out, "window-known", 1, 1) / kMetricsFile));
  EXPECT_GE(metrics.at("solves").get<int>(), kSteps - 1);
  EXPECT_LT(metrics.at("unconverged_solves").get<int>(), metrics.at("solves").get<int>());
}

// A window longer than the run is refused with the plan (the steps are known), before any run
// starts: no run folder is written.
TEST(WindowEstimatorRuns, AWindowLongerThanTheRunIsRefusedWithThePlan) {
  for (const std::string name : {"window-known", "window"}) {
    const fs::path out = datasets::testing::FreshTestDir();
    try {
      RunMonteCarlo(WindowPlan(name, {{"window_length", kSteps + 1}}), Quiet(out));
      ADD_FAILURE() << name << ": a window longer than the run accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("window_length"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("longer than the run"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(RunFolder(out, name, 1, 1))) << name;
  }
  // Zero and negative lengths are refused with the plan, before any run.
  for (const int length : {0, -5}) {
    const fs::path out = datasets::testing::FreshTestDir();
    try {
      RunMonteCarlo(WindowPlan("window", {{"window_length", length}}), Quiet(out));
      ADD_FAILURE() << "window_length " << length << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("window_length"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace phdslam::validation
