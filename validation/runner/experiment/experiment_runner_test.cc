#include "validation/runner/experiment/experiment_runner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "datasets/test_temp_dir.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/results/results_config.h"
#include "validation/runner/testing/results_testing.h"

namespace phdslam::validation {
namespace {

namespace fs = std::filesystem;
using testing::SplitLines;

Experiment OdometryExperiment() {
  Experiment x;
  x.name = "runner-test";
  x.scenario = "generated";
  x.estimators = {{"odometry", nlohmann::json::object(), {}}};
  x.seeds = {1, 2};
  x.steps = 20;
  x.jobs = 1;
  return x;
}

ExperimentSettings Quiet(const fs::path& out) {
  ExperimentSettings s;
  s.out = out;
  s.show_progress = false;
  s.report_failures = false;
  return s;
}

std::string ErrorOf(const Experiment& x, const fs::path& out) {
  try {
    PlanExperiment(x, out, EstimatorTable());
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(PlanExperiment, DeterministicEstimatorsRunOnceAtOneParticleBesideParticleFilters) {
  Experiment x = OdometryExperiment();
  x.estimators.insert(x.estimators.begin(), {"phd3", nlohmann::json::object(), {}});
  x.particles = {1, 10};
  const std::vector<ExperimentPart> parts = PlanExperiment(x, "/r", EstimatorTable());
  ASSERT_EQ(parts.size(), 1u);
  ASSERT_EQ(parts[0].plan.estimators.size(), 2u);
  EXPECT_TRUE(parts[0].plan.estimators[0].particles.empty());  // phd3: the experiment's 1, 10
  EXPECT_EQ(parts[0].plan.estimators[1].particles, std::vector<int>{1});  // odometry
  EXPECT_EQ(PlanJobs(parts[0].plan).size(), 2u * 3u);
  // The run says that odometry was held at N = 1 (its row's N is not a lost setting) ...
  EXPECT_FALSE(parts[0].plan.estimators[0].held_at_one_particle);
  EXPECT_TRUE(parts[0].plan.estimators[1].held_at_one_particle);
  // ... but not when every estimator runs at N = 1 anyway.
  x.particles = {1};
  EXPECT_FALSE(
      PlanExperiment(x, "/r", EstimatorTable())[0].plan.estimators[1].held_at_one_particle);
  // Alone, a deterministic estimator with another particle count is still refused.
  Experiment alone = OdometryExperiment();
  alone.particles = {5};
  const std::vector<ExperimentPart> planned = PlanExperiment(alone, "/r", EstimatorTable());
  MonteCarloSettings settings;
  settings.out = datasets::testing::FreshTestDir() / "alone";
  EXPECT_THROW(CheckMonteCarlo(planned[0].plan, settings), std::invalid_argument);
}

// A parameter bounded by the run's length is checked with the plan also when the data fix the
// length (steps = 0: the synthetic scenario's 4000 steps), before any run starts.
TEST(PlanExperiment, RunLengthBoundsAreCheckedWhenTheDataFixTheLength) {
  bool have_window = false;
  for (const EstimatorEntry& e : EstimatorTable()) have_window = have_window || e.name == "window";
  if (!have_window) GTEST_SKIP() << "built without Ceres";
  Experiment x = OdometryExperiment();
  x.scenario = "paper-synthetic";
  x.steps = 0;
  x.seeds = {1};
  x.estimators = {{"window", {{"window_length", 4001}}, {}}};
  const std::vector<ExperimentPart> parts = PlanExperiment(x, "/r", EstimatorTable());
  MonteCarloSettings settings;
  settings.out = datasets::testing::FreshTestDir() / "full";
  try {
    CheckMonteCarlo(parts[0].plan, settings);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("window_length: 4001 is longer than the run (4000 steps)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(settings.out / kSummaryFile));
  x.estimators = {{"window", {{"window_length", 4000}}, {}}};
  EXPECT_NO_THROW(CheckMonteCarlo(PlanExperiment(x, "/r", EstimatorTable())[0].plan, settings));
}

TEST(PlanExperiment, GridsAndRunCountsBeyondTheirCapsAreRefused) {
  Experiment x = OdometryExperiment();
  std::vector<nlohmann::json> values;
  for (int i = 1; i <= 1000; ++i) values.emplace_back(i);
  x.sweep = {ExperimentSweep{"clutter_rate", values}, ExperimentSweep{"speed", values}};
  std::string e = ErrorOf(x, "/r");
  EXPECT_NE(e.find("clutter_rate (1000) x speed (1000) has 1000000 points, more than the cap of "
                   "10000"),
            std::string::npos)
      << e;
  x = OdometryExperiment();
  x.seeds.clear();
  for (std::uint64_t s = 1; s <= 1'000'000; ++s) x.seeds.push_back(s);
  x.particles = {1, 2, 3};
  x.estimators = {{"phd3", nlohmann::json::object(), {}}};
  e = ErrorOf(x, "/r");
  EXPECT_NE(e.find("3000000 runs"), std::string::npos) << e;
}

TEST(PlanExperiment, OnePartOrOnePerSweepValue) {
  Experiment x = OdometryExperiment();
  std::vector<ExperimentPart> parts = PlanExperiment(x, "/r", EstimatorTable());
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_TRUE(parts[0].sweep_point.empty());
  EXPECT_EQ(parts[0].out, fs::path("/r"));
  EXPECT_EQ(parts[0].plan.experiment, "runner-test");
  EXPECT_EQ(parts[0].plan.scenario.options.at("steps"), 20);

  x.sweep = {ExperimentSweep{"pd", {0.3, 0.75, 1.0}}};
  parts = PlanExperiment(x, "/r", EstimatorTable());
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(parts[1].out, fs::path("/r/sweep-pd-0.75"));
  EXPECT_EQ(parts[2].out, fs::path("/r/sweep-pd-1"));
  EXPECT_EQ(parts[1].sweep_point, SweepPoint({0.75}));
  EXPECT_EQ(parts[1].plan.scenario.options.at("detection_probability"), 0.75);
  EXPECT_EQ(parts[0].plan.experiment, parts[2].plan.experiment);  // common random numbers
  EXPECT_EQ(SweepFolderName({{"clutter_rate", {0.0}}}, {0.0}), "sweep-clutter_rate-0");
}

TEST(PlanExperiment, GridsOverScenarioOptionsEstimatorParametersAndParticles) {
  Experiment x = OdometryExperiment();
  x.estimators = {{"phd3", {{"resampling", true}}, {5}}};
  x.scenario_settings = {{"speed", 2.0}};
  x.sweep = {ExperimentSweep{"landmarks", {10, 30}}, ExperimentSweep{"particles", {1, 4}},
             ExperimentSweep{"phd3:merge_threshold", {2, 8}}};
  const std::vector<ExperimentPart> parts = PlanExperiment(x, "/r", EstimatorTable());
  ASSERT_EQ(parts.size(), 8u);
  EXPECT_EQ(parts[0].out, fs::path("/r/sweep-landmarks-10-particles-1-phd3.merge_threshold-2"));
  EXPECT_EQ(parts[7].out, fs::path("/r/sweep-landmarks-30-particles-4-phd3.merge_threshold-8"));
  const ExperimentPart& p = parts[5];  // landmarks 30, particles 1, merge threshold 8
  EXPECT_EQ(p.sweep_point, SweepPoint({30, 1, 8}));
  EXPECT_EQ(p.plan.scenario.options.at("landmarks"), 30);
  EXPECT_EQ(p.plan.scenario.options.at("speed"), 2.0);
  EXPECT_EQ(p.plan.particles, std::vector<int>({1}));
  ASSERT_EQ(p.plan.estimators.size(), 1u);
  EXPECT_TRUE(p.plan.estimators[0].particles.empty());
  EXPECT_EQ(p.plan.estimators[0].overrides,
            (nlohmann::json{{"resampling", true}, {"merge_threshold", 8}}));
}

TEST(PlanExperiment, StepsAndPdSweepsAndTheirClashes) {
  Experiment x = OdometryExperiment();
  x.steps = 0;
  x.sweep = {ExperimentSweep{"steps", {10, 30}}, ExperimentSweep{"pd", {0.5}}};
  const std::vector<ExperimentPart> parts = PlanExperiment(x, "/r", EstimatorTable());
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[1].out, fs::path("/r/sweep-steps-30-pd-0.5"));
  EXPECT_EQ(parts[1].plan.scenario.options.at("steps"), 30);
  EXPECT_EQ(parts[1].plan.scenario.options.at("detection_probability"), 0.5);
  x.steps = 20;  // the swept step count is also set
  EXPECT_NE(ErrorOf(x, "/r").find("'steps' is swept"), std::string::npos);
  x = OdometryExperiment();
  x.estimators = {{"phd3", {{"max_hypotheses", 7}}, {}}};
  x.sweep = {ExperimentSweep{"max_hypotheses", {5}}};
  EXPECT_NE(ErrorOf(x, "/r").find("'max_hypotheses' is swept"), std::string::npos);
  x = OdometryExperiment();
  x.pd = 0.8;
  x.sweep = {ExperimentSweep{"detection_probability", {0.5}}};
  EXPECT_NE(ErrorOf(x, "/r").find("'pd' and 'detection_probability' both set"), std::string::npos);
}

TEST(PlanExperiment, ErrorsNameTheExperimentFile) {
  Experiment x = OdometryExperiment();
  x.estimators.push_back({"nosuch", nlohmann::json::object(), {}});
  EXPECT_NE(ErrorOf(x, "/r").find("unknown estimator 'nosuch'"), std::string::npos);
  x.source = {{"path", "experiments/t.yaml"}};
  std::string e = ErrorOf(x, "/r");
  EXPECT_EQ(e.rfind("experiments/t.yaml: unknown estimator 'nosuch' (known: ", 0), 0u) << e;

  x = OdometryExperiment();
  x.pd = 0.9;
  x.sweep = {ExperimentSweep{"pd", {0.5}}};
  EXPECT_NE(ErrorOf(x, "/r").find("'pd' is swept"), std::string::npos);
  x.sweep = {ExperimentSweep{"spede", {0.5}}};
  e = ErrorOf(x, "/r");
  EXPECT_NE(e.find("sweep parameter 'spede' (value 0.5) is not particles"), std::string::npos) << e;
  EXPECT_NE(e.find("speed"), std::string::npos) << e;  // the scenario's options are listed
  x = OdometryExperiment();
  x.sweep = {ExperimentSweep{"landmarks", {10, 20.5}}};  // wrong type, found before any run
  e = ErrorOf(x, "/r");
  EXPECT_NE(e.find("'landmarks': expected an integer, got 20.5"), std::string::npos) << e;
  x.sweep = {ExperimentSweep{"particles", {"many"}}};
  e = ErrorOf(x, "/r");
  EXPECT_NE(e.find("sweep parameter 'particles'"), std::string::npos) << e;
  x.sweep = {ExperimentSweep{"landmarks", {}}};
  EXPECT_NE(ErrorOf(x, "/r").find("'landmarks' has no values"), std::string::npos);
  x.sweep = {ExperimentSweep{"nosuch:gate", {1}}};
  EXPECT_NE(ErrorOf(x, "/r").find("estimator 'nosuch' is not among"), std::string::npos);
  x = OdometryExperiment();
  x.scenario_settings = {{"speed", 2.0}};
  x.sweep = {ExperimentSweep{"speed", {1.0}}};
  EXPECT_NE(ErrorOf(x, "/r").find("'speed' is swept"), std::string::npos);
  x = OdometryExperiment();
  x.scenario_settings = {{"speeed", 2.0}};
  e = ErrorOf(x, "/r");
  EXPECT_NE(e.find("unknown parameter 'speeed'"), std::string::npos) << e;
  x = OdometryExperiment();
  x.sweep = {ExperimentSweep{"pd", {0.5, 1.5}}};  // pD out of range, found before any run
  EXPECT_FALSE(ErrorOf(x, "/r").empty());
  x = OdometryExperiment();
  x.scenario = "nosuch";
  EXPECT_NE(ErrorOf(x, "/r").find("nosuch"), std::string::npos);
}

TEST(RunExperiment, SweepWritesAFolderPerValueAndTheSweepTable) {
  const fs::path out = datasets::testing::FreshTestDir();
  Experiment x = OdometryExperiment();
  x.sweep = {ExperimentSweep{"clutter_rate", {0, 2.5}}};
  x.source = {{"path", "sweep.yaml"}, {"text", "..."}};
  const ExperimentReport report = RunExperiment(x, Quiet(out));
  ASSERT_EQ(report.reports.size(), 2u);
  EXPECT_EQ(report.reports[0].finished, 2u);
  EXPECT_FALSE(report.interrupted);
  for (const char* folder : {"sweep-clutter_rate-0", "sweep-clutter_rate-2.5"}) {
    EXPECT_TRUE(fs::exists(out / folder / kSummaryFile)) << folder;
    EXPECT_TRUE(fs::exists(RunFolder(out / folder, "odometry", 1, 2) / kMetricsFile)) << folder;
  }
  const nlohmann::json config = ReadJsonObject(out / "sweep-clutter_rate-2.5" / kConfigFile);
  EXPECT_EQ(config.at("scenario").at("options").at("clutter_rate"), 2.5);
  EXPECT_EQ(config.at("experiment_file").at("path"), "sweep.yaml");

  const std::vector<std::string> table = SplitLines(ReadTextFile(out / kSweepTableFile));
  const std::vector<std::string> first =
      SplitLines(ReadTextFile(out / "sweep-clutter_rate-0" / kSummaryFile));
  const std::vector<std::string> second =
      SplitLines(ReadTextFile(out / "sweep-clutter_rate-2.5" / kSummaryFile));
  ASSERT_EQ(table.size(), 3u);
  EXPECT_EQ(table[0], "clutter_rate," + first[0]);
  EXPECT_EQ(table[1], "0," + first[1]);
  EXPECT_EQ(table[2], "2.5," + second[1]);
  const nlohmann::json sweep = ReadJsonObject(out / kSweepFile);
  EXPECT_EQ(sweep.at("parameter"), "clutter_rate");
  EXPECT_EQ(sweep.at("folders"),
            nlohmann::json({"sweep-clutter_rate-0", "sweep-clutter_rate-2.5"}));

  // Resume: nothing is recomputed.
  const ExperimentReport again = RunExperiment(x, Quiet(out));
  EXPECT_EQ(again.reports[0].skipped, 2u);
  EXPECT_EQ(again.reports[1].finished, 0u);
}

TEST(RunExperiment, GridWritesOneColumnPerParameter) {
  const fs::path out = datasets::testing::FreshTestDir();
  Experiment x = OdometryExperiment();
  x.seeds = {1};
  x.sweep = {ExperimentSweep{"clutter_rate", {0, 3}}, ExperimentSweep{"speed", {0.5, 2}}};
  RunExperiment(x, Quiet(out));
  const std::vector<std::string> table = SplitLines(ReadTextFile(out / kSweepTableFile));
  const std::vector<std::string> last =
      SplitLines(ReadTextFile(out / "sweep-clutter_rate-3-speed-2" / kSummaryFile));
  ASSERT_EQ(table.size(), 5u);
  EXPECT_EQ(table[0], "clutter_rate,speed," + last[0]);
  EXPECT_EQ(table[4], "3,2," + last[1]);
  EXPECT_EQ(table[2].rfind("0,2,odometry,1,", 0), 0u) << table[2];
  const nlohmann::json config = ReadJsonObject(out / "sweep-clutter_rate-3-speed-2" / kConfigFile);
  EXPECT_EQ(config.at("scenario").at("options").at("speed"), 2.0);
  EXPECT_EQ(config.at("scenario").at("options").at("clutter_rate"), 3.0);
  const nlohmann::json sweep = ReadJsonObject(out / kSweepFile);
  EXPECT_EQ(sweep.at("parameters").size(), 2u);
  EXPECT_FALSE(sweep.contains("parameter"));
  EXPECT_EQ(ReadSweepFile(out).at(1).parameter, "speed");
  // The speed changes the trajectory: the runs differ.
  const CsvTable slow = ReadCsvFile(out / "sweep-clutter_rate-0-speed-0.5" / kRunsTableFile);
  const CsvTable fast = ReadCsvFile(out / "sweep-clutter_rate-0-speed-2" / kRunsTableFile);
  EXPECT_NE(slow.rows.at(0), fast.rows.at(0));
}

TEST(RunExperiment, ChecksEveryPartBeforeRunningAny) {
  const fs::path out = datasets::testing::FreshTestDir();
  Experiment x = OdometryExperiment();
  x.sweep = {ExperimentSweep{"pd", {0.5, 0.9}}};
  // The second value's folder holds other results: nothing may run.
  Experiment other = OdometryExperiment();
  other.name = "someone-else";
  other.pd = 0.9;
  RunExperiment(other, Quiet(out / "sweep-pd-0.9"));
  EXPECT_THROW(RunExperiment(x, Quiet(out)), std::invalid_argument);
  EXPECT_FALSE(fs::exists(out / "sweep-pd-0.5"));
}

TEST(RunExperiment, ShardsPartitionTheJobsOfEverySweepValue) {
  // 2 values x 2 seeds = 4 jobs; shard 1/3 gets global jobs 0 and 3, i.e. value 0.5 seed 1
  // and value 0.9 seed 2.
  const fs::path out = datasets::testing::FreshTestDir();
  Experiment x = OdometryExperiment();
  x.sweep = {ExperimentSweep{"pd", {0.5, 0.9}}};
  ExperimentSettings s = Quiet(out);
  s.shard = Shard{1, 3};
  const ExperimentReport report = RunExperiment(x, s);
  EXPECT_EQ(report.reports[0].planned, 1u);
  EXPECT_EQ(report.reports[1].planned, 1u);
  EXPECT_TRUE(fs::exists(RunFolder(out / "sweep-pd-0.5", "odometry", 1, 1) / kMetricsFile));
  EXPECT_FALSE(fs::exists(RunFolder(out / "sweep-pd-0.5", "odometry", 1, 2)));
  EXPECT_TRUE(fs::exists(RunFolder(out / "sweep-pd-0.9", "odometry", 1, 2) / kMetricsFile));
  const nlohmann::json timing = ReadJsonObject(out / "sweep-pd-0.9" / kTimingFile);
  EXPECT_EQ(timing.at("shard"), "1/3");
  EXPECT_EQ(timing.at("runs_outside_shard"), 1);
}

TEST(RunExperiment, ParticleTracesOfParticleFilters) {
  const fs::path out = datasets::testing::FreshTestDir();
  Experiment x = OdometryExperiment();
  x.estimators = {{"phd3", nlohmann::json::object(), {4}},
                  {"odometry", nlohmann::json::object(), {}}};
  x.seeds = {1};
  ExperimentSettings s = Quiet(out);
  s.particles_trace = true;
  RunExperiment(x, s);
  const CsvTable trace = ReadCsvFile(RunFolder(out, "phd3", 4, 1) / kParticlesFile);
  EXPECT_EQ(trace.header, std::vector<std::string>({"step", "particle", "x", "y", "log_weight"}));
  ASSERT_EQ(trace.rows.size(), 20u * 4u);
  EXPECT_EQ(trace.rows[5][0], "1");
  EXPECT_EQ(trace.rows[5][1], "1");
  // The weights of each step sum to one.
  for (std::size_t k = 0; k < 20; ++k) {
    double total = 0.0;
    for (std::size_t i = 0; i < 4; ++i) total += std::exp(std::stod(trace.rows[4 * k + i][4]));
    EXPECT_NEAR(total, 1.0, 1e-8) << "step " << k;
  }
  // Odometry has no particles: no file.
  EXPECT_FALSE(fs::exists(RunFolder(out, "odometry", 1, 1) / kParticlesFile));
}

}  // namespace
}  // namespace phdslam::validation
