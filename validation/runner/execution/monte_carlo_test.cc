#include "validation/runner/execution/monte_carlo.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <new>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/data_dir.h"
#include "datasets/test_data_sets.h"
#include "datasets/test_temp_dir.h"
#include "src/core/random.h"
#include "validation/runner/io/list_arguments.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/registry/parameter_overrides.h"
#include "validation/runner/results/results_config.h"
#include "validation/runner/results/results_lock.h"

namespace phdslam::validation {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSummaryHeaderStart =
    "estimator,particles,runs,steps,pos_rmse_m,heading_rmse_deg,gospa_mean_m,gospa_std_m,"
    "ess_pct,resampling_pct,ms_per_step_mean,";

MonteCarloPlan OdometryPlan(const std::string& scenario, int steps,
                            std::vector<std::uint64_t> seeds) {
  MonteCarloPlan plan;
  ScenarioOptions options;
  options.steps = steps;
  plan.scenario = MakeScenarioSource(scenario, options);
  plan.estimators = {{FindEstimator("odometry"), nlohmann::json::object()}};
  plan.particles = {1};
  plan.seeds = std::move(seeds);
  return plan;
}

MonteCarloSettings Quiet(const fs::path& out, int jobs) {
  MonteCarloSettings s;
  s.out = out;
  s.jobs = jobs;
  s.show_progress = false;
  s.report_failures = false;
  return s;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::vector<std::string> Cells(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return cells;
}

// The CSV without its timing columns ("ms" and "ms_*").
std::string WithoutTiming(const std::string& csv) {
  const std::vector<std::string> lines = Lines(csv);
  if (lines.empty()) return "";
  const std::vector<std::string> header = Cells(lines[0]);
  std::string out;
  for (const std::string& line : lines) {
    const std::vector<std::string> cells = Cells(line);
    EXPECT_EQ(cells.size(), header.size()) << line;
    for (std::size_t i = 0; i < cells.size() && i < header.size(); ++i) {
      if (header[i] == "ms" || header[i].rfind("ms_", 0) == 0) continue;
      out += cells[i] + ",";
    }
    out += "\n";
  }
  return out;
}

nlohmann::json WithoutTiming(nlohmann::json j) {
  for (auto it = j.begin(); it != j.end();) {
    it = it.key().rfind("ms_", 0) == 0 ? j.erase(it) : std::next(it);
  }
  return j;
}

std::string FirstLine(const fs::path& path) { return Lines(ReadTextFile(path)).at(0); }

// An online estimator that stands still and throws at step 3 of seed `failing_seed`: a
// runtime_error, or std::bad_alloc when `out_of_memory`.
class StillEstimator final : public filters::OnlineEstimator {
 public:
  StillEstimator(const datasets::Scenario& s, std::uint64_t failing_seed, bool out_of_memory)
      : pose_(s.initial_pose), fail_(s.seed == failing_seed), out_of_memory_(out_of_memory) {}
  filters::StepOutput Step(const datasets::StepData&) override {
    if (fail_ && ++steps_ == 3) {
      if (out_of_memory_) throw std::bad_alloc();
      throw std::runtime_error("diverged at step 3");
    }
    filters::StepOutput out;
    out.pose = pose_;
    return out;
  }
  [[nodiscard]] filters::MapEstimate Map() const override { return {}; }

 private:
  Pose pose_;
  bool fail_;
  bool out_of_memory_;
  int steps_ = 0;
};

EstimatorEntry StillEntry(const std::uint64_t* failing_seed, bool out_of_memory = false) {
  EstimatorEntry e;
  e.name = "still";
  e.description = "stands at the initial pose";
  // It fails on one seed, so it reads the scenario's seed: a truth-reading entry.
  e.reads_truth = true;
  e.make_online_with_truth = [failing_seed, out_of_memory](const EstimatorRequest&,
                                                           const datasets::Scenario& s) {
    return std::make_unique<StillEstimator>(s, *failing_seed, out_of_memory);
  };
  e.resolved_parameters = [](const EstimatorRequest& r) {
    return ApplyOverrides(nlohmann::json{{"speed", 0.0}}, r.overrides, "still");
  };
  return e;
}

// An online estimator whose poses are random draws from its stream: any dependence of the stream
// on threads or job order would show in the results.
class RandomWalkEstimator final : public filters::OnlineEstimator {
 public:
  RandomWalkEstimator(const filters::EstimatorContext& c, std::uint64_t stream_seed, int particles)
      : pose_(c.initial_pose), stream_(stream_seed), particles_(particles) {}
  filters::StepOutput Step(const datasets::StepData&) override {
    pose_ += Pose(stream_.Normal(), stream_.Normal(), 0.01 * stream_.Normal());
    filters::StepOutput out;
    out.pose = pose_;
    out.diag.ess = particles_ * stream_.Uniform();
    out.diag.resampled = stream_.Uniform() < 0.5;
    return out;
  }
  [[nodiscard]] filters::MapEstimate Map() const override {
    filters::MapEstimate m;
    m.means = {pose_.head<2>()};
    m.covs = {Mat2::Identity()};
    m.log_weights = {-1.0};
    return m;
  }

 private:
  Pose pose_;
  RandomStream stream_;
  int particles_;
};

EstimatorEntry RandomWalkEntry() {
  EstimatorEntry e;
  e.name = "walk";
  e.description = "random walk from the estimator's stream";
  e.make_online = [](const EstimatorRequest& r) {
    return std::make_unique<RandomWalkEstimator>(*r.context, r.stream_seed, r.particles);
  };
  e.resolved_parameters = [](const EstimatorRequest&) { return nlohmann::json::object(); };
  return e;
}

TEST(MonteCarlo, OdometryRunWritesEveryFileWithItsHeader) {
  const fs::path out = datasets::testing::FreshTestDir();
  const MonteCarloReport report =
      RunMonteCarlo(OdometryPlan("paper-synthetic", 200, {1, 2, 3}), Quiet(out, 2));
  EXPECT_EQ(report.planned, 3u);
  EXPECT_EQ(report.finished, 3u);
  EXPECT_EQ(report.skipped, 0u);
  EXPECT_TRUE(report.failures.empty());
  EXPECT_FALSE(report.interrupted);

  for (std::uint64_t seed : {1, 2, 3}) {
    const fs::path run = RunFolder(out, "odometry", 1, seed);
    const std::vector<std::string> steps = Lines(ReadTextFile(run / kStepsFile));
    ASSERT_EQ(steps.size(), 201u);
    EXPECT_EQ(steps[0],
              "step,t,x,y,theta,x_true,y_true,theta_true,pos_err_m,heading_err_deg,ess,resampled,"
              "hypotheses,map_components,ms,nees,nees_rb,nis_sum,nis_count,gps_nees_rb");
    EXPECT_EQ(Cells(steps[1]).size(), 20u);
    EXPECT_EQ(steps[1].rfind("0,0,300,400,", 0), 0u) << steps[1];  // the initial pose
    EXPECT_EQ(FirstLine(run / kTrajectoryFile), "# t x y z qx qy qz qw");
    EXPECT_EQ(Lines(ReadTextFile(run / kTrajectoryFile)).size(), 201u);
    EXPECT_EQ(FirstLine(run / kMapFile), "x,y,weight,pxx,pxy,pyy");
    const nlohmann::json metrics = nlohmann::json::parse(ReadTextFile(run / kMetricsFile));
    EXPECT_EQ(metrics.at("estimator"), "odometry");
    EXPECT_EQ(metrics.at("seed"), seed);
    EXPECT_EQ(metrics.at("steps"), 200);
    EXPECT_EQ(metrics.at("stream_seed"), RunStreamSeed("default", seed, "odometry", 1));
    EXPECT_EQ(metrics.at("truth_map_size"), 160);
    EXPECT_GT(metrics.at("pos_rmse_m").get<double>(), 0.0);
    EXPECT_GT(metrics.at("gospa_m").get<double>(), 0.0);
    // Dead reckoning has no particles: no ESS and no resampling rate (written as null).
    EXPECT_TRUE(metrics.at("ess_pct").is_null());
    EXPECT_TRUE(metrics.at("resampling_pct").is_null());
    EXPECT_FALSE(fs::exists(run / kErrorFile));
    EXPECT_EQ(Lines(ReadTextFile(TruthFolder(out, seed) / kTruthTrajectoryFile)).size(), 201u);
  }
  EXPECT_EQ(FirstLine(out / kTruthMapFile), "x,y,weight,pxx,pxy,pyy");
  EXPECT_EQ(Lines(ReadTextFile(out / kTruthMapFile)).size(), 161u);

  const std::vector<std::string> summary = Lines(ReadTextFile(out / kSummaryFile));
  ASSERT_EQ(summary.size(), 2u);
  EXPECT_EQ(summary[0].rfind(kSummaryHeaderStart, 0), 0u) << summary[0];
  EXPECT_EQ(summary[1].rfind("odometry,1,3,200,", 0), 0u) << summary[1];
  const std::vector<std::string> runs = Lines(ReadTextFile(out / kRunsTableFile));
  ASSERT_EQ(runs.size(), 4u);
  EXPECT_EQ(runs[0].rfind("estimator,particles,seed,steps,pos_rmse_m,", 0), 0u) << runs[0];
  EXPECT_EQ(runs[2].rfind("odometry,1,2,200,", 0), 0u) << runs[2];

  const nlohmann::json config = nlohmann::json::parse(ReadTextFile(out / kConfigFile));
  EXPECT_EQ(config.at("experiment"), "default");
  EXPECT_EQ(config.at("scenario").at("name"), "paper-synthetic");
  EXPECT_EQ(config.at("scenario").at("options").at("steps"), 200);
  EXPECT_EQ(config.at("scenario").at("options").at("detection_probability"), 0.95);
  EXPECT_EQ(config.at("seeds"), nlohmann::json({1, 2, 3}));
  EXPECT_EQ(config.at("particles"), nlohmann::json({1}));
  EXPECT_TRUE(config.at("estimators").contains("odometry"));
  EXPECT_EQ(config.at("program").at("version"), ProgramVersion());
  const nlohmann::json timing = nlohmann::json::parse(ReadTextFile(out / kTimingFile));
  EXPECT_EQ(timing.at("runs_finished"), 3);
  EXPECT_EQ(timing.at("jobs"), 2);
}

TEST(MonteCarlo, ResultsDoNotDependOnTheNumberOfJobs) {
  const fs::path base = datasets::testing::FreshTestDir();
  const MonteCarloPlan plan = OdometryPlan("paper-synthetic", 200, {1, 2, 3});
  RunMonteCarlo(plan, Quiet(base / "one", 1));
  RunMonteCarlo(plan, Quiet(base / "two", 2));
  for (const char* file : {kSummaryFile, kRunsTableFile}) {
    const std::string one = ReadTextFile(base / "one" / file);
    const std::string two = ReadTextFile(base / "two" / file);
    EXPECT_EQ(WithoutTiming(one), WithoutTiming(two)) << file;
    EXPECT_NE(WithoutTiming(one).find("odometry"), std::string::npos);
  }
  for (std::uint64_t seed : {1, 2, 3}) {
    const fs::path a = RunFolder(base / "one", "odometry", 1, seed);
    const fs::path b = RunFolder(base / "two", "odometry", 1, seed);
    EXPECT_EQ(WithoutTiming(ReadTextFile(a / kStepsFile)),
              WithoutTiming(ReadTextFile(b / kStepsFile)));
    EXPECT_EQ(ReadTextFile(a / kTrajectoryFile), ReadTextFile(b / kTrajectoryFile));
    EXPECT_EQ(ReadTextFile(a / kMapFile), ReadTextFile(b / kMapFile));
    EXPECT_EQ(WithoutTiming(nlohmann::json::parse(ReadTextFile(a / kMetricsFile))),
              WithoutTiming(nlohmann::json::parse(ReadTextFile(b / kMetricsFile))));
  }
}

TEST(MonteCarlo, RandomEstimatorsGiveTheSameFilesForAnyNumberOfJobs) {
  const fs::path base = datasets::testing::FreshTestDir();
  MonteCarloPlan plan = OdometryPlan("generated", 50, {1, 2, 3, 4, 5});
  plan.estimators = {{RandomWalkEntry(), nlohmann::json::object()}};
  plan.particles = {1, 10};
  RunMonteCarlo(plan, Quiet(base / "one", 1));
  RunMonteCarlo(plan, Quiet(base / "two", 2));
  const std::string runs = ReadTextFile(base / "one" / kRunsTableFile);
  EXPECT_EQ(Lines(runs).size(), 11u);
  EXPECT_EQ(WithoutTiming(runs), WithoutTiming(ReadTextFile(base / "two" / kRunsTableFile)));
  EXPECT_EQ(WithoutTiming(ReadTextFile(base / "one" / kSummaryFile)),
            WithoutTiming(ReadTextFile(base / "two" / kSummaryFile)));
  for (int n : {1, 10}) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      EXPECT_EQ(ReadTextFile(RunFolder(base / "one", "walk", n, seed) / kTrajectoryFile),
                ReadTextFile(RunFolder(base / "two", "walk", n, seed) / kTrajectoryFile));
    }
  }
  // Different seeds and particle counts do draw different streams.
  EXPECT_NE(ReadTextFile(RunFolder(base / "one", "walk", 1, 1) / kTrajectoryFile),
            ReadTextFile(RunFolder(base / "one", "walk", 10, 1) / kTrajectoryFile));
  EXPECT_NE(ReadTextFile(RunFolder(base / "one", "walk", 1, 1) / kTrajectoryFile),
            ReadTextFile(RunFolder(base / "one", "walk", 1, 2) / kTrajectoryFile));
}

TEST(MonteCarlo, RerunSkipsFinishedRunsAndRecomputesDeletedOnes) {
  const fs::path out = datasets::testing::FreshTestDir();
  const MonteCarloPlan plan = OdometryPlan("paper-synthetic", 200, {1, 2, 3});
  RunMonteCarlo(plan, Quiet(out, 2));
  const fs::path metrics2 = RunFolder(out, "odometry", 1, 2) / kMetricsFile;
  const fs::path steps1 = RunFolder(out, "odometry", 1, 1) / kStepsFile;
  // Mark the files so that a rewrite is visible whatever the file system's time resolution.
  const auto old_time = fs::file_time_type::clock::now() - std::chrono::hours(1);
  fs::last_write_time(metrics2, old_time);
  fs::last_write_time(steps1, old_time);
  const std::string summary = ReadTextFile(out / kSummaryFile);

  MonteCarloReport again = RunMonteCarlo(plan, Quiet(out, 2));
  EXPECT_EQ(again.skipped, 3u);
  EXPECT_EQ(again.finished, 0u);
  EXPECT_EQ(fs::last_write_time(metrics2), old_time);
  EXPECT_EQ(fs::last_write_time(steps1), old_time);
  EXPECT_EQ(WithoutTiming(ReadTextFile(out / kSummaryFile)), WithoutTiming(summary));

  // A run without metrics.json is not finished: it is computed again, the others are not.
  const std::string metrics1_before = ReadTextFile(RunFolder(out, "odometry", 1, 1) / kMetricsFile);
  fs::remove(RunFolder(out, "odometry", 1, 1) / kMetricsFile);
  again = RunMonteCarlo(plan, Quiet(out, 2));
  EXPECT_EQ(again.skipped, 2u);
  EXPECT_EQ(again.finished, 1u);
  EXPECT_NE(fs::last_write_time(steps1), old_time);
  EXPECT_EQ(fs::last_write_time(metrics2), old_time);
  EXPECT_EQ(WithoutTiming(nlohmann::json::parse(metrics1_before)),
            WithoutTiming(nlohmann::json::parse(
                ReadTextFile(RunFolder(out, "odometry", 1, 1) / kMetricsFile))));

  // New seeds are added to the same folder; config.json lists the union.
  const MonteCarloReport more =
      RunMonteCarlo(OdometryPlan("paper-synthetic", 200, {3, 4}), Quiet(out, 1));
  EXPECT_EQ(more.skipped, 1u);
  EXPECT_EQ(more.finished, 1u);
  const nlohmann::json config = nlohmann::json::parse(ReadTextFile(out / kConfigFile));
  EXPECT_EQ(config.at("seeds"), nlohmann::json({1, 2, 3, 4}));
  EXPECT_EQ(Lines(ReadTextFile(out / kRunsTableFile)).size(), 5u);
}

TEST(MonteCarlo, RefusesToMixResultsOfOtherSettings) {
  const fs::path out = datasets::testing::FreshTestDir();
  RunMonteCarlo(OdometryPlan("generated", 20, {1}), Quiet(out, 1));
  EXPECT_THROW(RunMonteCarlo(OdometryPlan("generated", 30, {1}), Quiet(out, 1)),
               std::invalid_argument);
  MonteCarloPlan other_experiment = OdometryPlan("generated", 20, {2});
  other_experiment.experiment = "another";
  EXPECT_THROW(RunMonteCarlo(other_experiment, Quiet(out, 1)), std::invalid_argument);
  EXPECT_THROW(RunMonteCarlo(OdometryPlan("paper-synthetic", 20, {1}), Quiet(out, 1)),
               std::invalid_argument);
  // Nothing new was written.
  EXPECT_FALSE(fs::exists(RunFolder(out, "odometry", 1, 2)));
}

TEST(MonteCarlo, AFailingRunIsReportedAndTheOthersGoOn) {
  const fs::path out = datasets::testing::FreshTestDir();
  std::uint64_t failing_seed = 2;
  MonteCarloPlan plan = OdometryPlan("generated", 20, {1, 2, 3});
  plan.estimators = {{StillEntry(&failing_seed), nlohmann::json::object()}};
  const MonteCarloReport report = RunMonteCarlo(plan, Quiet(out, 2));
  EXPECT_EQ(report.finished, 2u);
  ASSERT_EQ(report.failures.size(), 1u);
  EXPECT_EQ(report.failures[0].estimator, "still");
  EXPECT_EQ(report.failures[0].seed, 2u);
  EXPECT_NE(report.failures[0].error.find("diverged at step 3"), std::string::npos);
  const fs::path failed = RunFolder(out, "still", 1, 2);
  EXPECT_FALSE(fs::exists(failed / kMetricsFile));
  const nlohmann::json error = nlohmann::json::parse(ReadTextFile(failed / kErrorFile));
  EXPECT_EQ(error.at("seed"), 2);
  EXPECT_NE(error.at("error").get<std::string>().find("diverged"), std::string::npos);
  EXPECT_TRUE(fs::exists(RunFolder(out, "still", 1, 3) / kMetricsFile));
  const std::vector<std::string> summary = Lines(ReadTextFile(out / kSummaryFile));
  ASSERT_EQ(summary.size(), 2u);
  const std::vector<std::string> header = Cells(summary[0]);
  const std::vector<std::string> row = Cells(summary[1]);
  const auto column = [&](const std::string& name) {
    return row.at(
        static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin()));
  };
  EXPECT_EQ(column("runs"), "2");
  EXPECT_EQ(column("failed_runs"), "1");

  // Rerun once the cause is gone: only the failed run is computed; error.json disappears.
  failing_seed = 99;
  const MonteCarloReport rerun = RunMonteCarlo(plan, Quiet(out, 2));
  EXPECT_EQ(rerun.finished, 1u);
  EXPECT_EQ(rerun.skipped, 2u);
  EXPECT_TRUE(rerun.failures.empty());
  EXPECT_TRUE(fs::exists(failed / kMetricsFile));
  EXPECT_FALSE(fs::exists(failed / kErrorFile));
}

// Out of memory inside a run is an orderly stop: that run's error.json says so in words a user
// can act on, no further run starts, the finished runs and the summary are kept, no temporary
// file is left behind, and a rerun computes the rest.
TEST(MonteCarlo, OutOfMemoryInARunIsAnOrderlyStop) {
  const fs::path out = datasets::testing::FreshTestDir();
  std::uint64_t failing_seed = 2;
  MonteCarloPlan plan = OdometryPlan("generated", 20, {1, 2, 3});
  plan.estimators = {{StillEntry(&failing_seed, /*out_of_memory=*/true), nlohmann::json::object()}};
  try {
    RunMonteCarlo(plan, Quiet(out, 1));  // one job: seeds in order, seed 3 never starts
    ADD_FAILURE() << "out of memory was not reported";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no further run was started"), std::string::npos) << what;
    EXPECT_NE(what.find("fewer --jobs"), std::string::npos) << what;
  }
  const std::string why =
      nlohmann::json::parse(ReadTextFile(RunFolder(out, "still", 1, 2) / kErrorFile))
          .at("error")
          .get<std::string>();
  EXPECT_NE(why.find("out of memory (std::bad_alloc)"), std::string::npos) << why;
  EXPECT_NE(why.find("fewer particles"), std::string::npos) << why;
  EXPECT_TRUE(fs::exists(RunFolder(out, "still", 1, 1) / kMetricsFile));
  EXPECT_FALSE(fs::exists(RunFolder(out, "still", 1, 3)));
  EXPECT_EQ(Lines(ReadTextFile(out / kSummaryFile)).size(), 2u);
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
  failing_seed = 99;
  const MonteCarloReport rerun = RunMonteCarlo(plan, Quiet(out, 2));
  EXPECT_EQ(rerun.finished, 2u);
  EXPECT_EQ(rerun.skipped, 1u);
  EXPECT_TRUE(rerun.failures.empty());
}

// Temporary files of a killed process are removed by the next run of the folder.
TEST(MonteCarlo, LeftoverTemporaryFilesAreRemoved) {
  const fs::path out = datasets::testing::FreshTestDir();
  RunMonteCarlo(OdometryPlan("generated", 20, {1}), Quiet(out, 1));
  const fs::path folder = RunFolder(out, "odometry", 1, 1);
  WriteFileAtomically(folder / "keep.txt", "kept\n");
  { std::ofstream(folder / "metrics.json.tmp-3") << "{"; }
  { std::ofstream(out / "runs.csv.tmp-merge") << "x"; }
  EXPECT_EQ(RemoveLeftoverTemporaries(out), 2u);
  EXPECT_FALSE(fs::exists(folder / "metrics.json.tmp-3"));
  EXPECT_TRUE(fs::exists(folder / "keep.txt"));
  { std::ofstream(folder / "steps.csv.tmp-0") << "x"; }
  const MonteCarloReport again =
      RunMonteCarlo(OdometryPlan("generated", 20, {1, 2}), Quiet(out, 1));
  EXPECT_EQ(again.finished, 1u);
  EXPECT_FALSE(fs::exists(folder / "steps.csv.tmp-0"));
}

TEST(MonteCarlo, StopFlagLetsNoNewRunStart) {
  const fs::path out = datasets::testing::FreshTestDir();
  std::atomic<bool> stop{true};
  MonteCarloSettings settings = Quiet(out, 2);
  settings.stop = &stop;
  const MonteCarloReport report = RunMonteCarlo(OdometryPlan("generated", 20, {1, 2}), settings);
  EXPECT_TRUE(report.interrupted);
  EXPECT_EQ(report.finished, 0u);
  EXPECT_EQ(Lines(ReadTextFile(out / kSummaryFile)).size(), 1u);  // header only
  stop = false;
  const MonteCarloReport resumed = RunMonteCarlo(OdometryPlan("generated", 20, {1, 2}), settings);
  EXPECT_FALSE(resumed.interrupted);
  EXPECT_EQ(resumed.finished, 2u);
}

TEST(MonteCarlo, AnOverflowingErrorIsAFailedRunNotAPoisonedFolder) {
  const fs::path out = datasets::testing::FreshTestDir();
  MonteCarloPlan plan = OdometryPlan("generated", 20, {1, 2});
  const auto make = plan.scenario.make;
  plan.scenario.make = [make](std::uint64_t seed) {
    datasets::Scenario s = make(seed);
    if (seed == 2) s.steps[5].data.controls.front()(0) = 1e200;  // finite, but its square is not
    return s;
  };
  const MonteCarloReport report = RunMonteCarlo(plan, Quiet(out, 1));
  EXPECT_EQ(report.finished, 1u);
  ASSERT_EQ(report.failures.size(), 1u);
  EXPECT_EQ(report.failures[0].seed, 2u);
  EXPECT_NE(report.failures[0].error.find("position error is not finite"), std::string::npos)
      << report.failures[0].error;
  EXPECT_FALSE(fs::exists(RunFolder(out, "odometry", 1, 2) / kMetricsFile));
  // The folder stays usable: the summary is written now and again on resume.
  EXPECT_NE(ReadTextFile(out / kSummaryFile).find("odometry,1,1,"), std::string::npos);
  EXPECT_NO_THROW(RunMonteCarlo(plan, Quiet(out, 1)));
  EXPECT_EQ(Lines(ReadTextFile(out / kRunsTableFile)).size(), 2u);  // header + the finished run
}

TEST(MonteCarlo, ResumeRefusesOtherDataFiles) {
  const fs::path root = datasets::testing::FreshTestDir();
  const fs::path data = root / "data";
  const fs::path mat = data / "phdslam3-synthetic" / "Environment_SLAM.mat";
  fs::create_directories(mat.parent_path());
  fs::copy_file(
      datasets::testing::SyntheticDataDir() / "phdslam3-synthetic" / "Environment_SLAM.mat", mat);
  const auto plan = [&](const fs::path& folder = {}, int steps = 5) {
    MonteCarloPlan p = OdometryPlan("generated", 5, {1});
    ScenarioOptions options;
    options.steps = steps;
    options.data_dir = (folder.empty() ? data : folder).string();
    p.scenario = MakeScenarioSource("paper-synthetic", options);
    return p;
  };
  const fs::path out = root / "out";
  EXPECT_EQ(RunMonteCarlo(plan(), Quiet(out, 1)).finished, 1u);
  const nlohmann::json config = ReadJsonObject(out / kConfigFile);
  const std::string checksum = config.at("scenario")
                                   .at("options")
                                   .at("data_files")
                                   .at("phdslam3-synthetic/Environment_SLAM.mat");
  EXPECT_EQ(checksum.rfind("sha256:", 0), 0u) << checksum;
  EXPECT_EQ(checksum.size(), 7u + 64u);
  // The same content elsewhere is the same data: a conflict names the setting that differs, not
  // the data folder.
  const fs::path moved = root / "moved";
  fs::create_directories(moved / "phdslam3-synthetic");
  fs::copy_file(mat, moved / "phdslam3-synthetic" / "Environment_SLAM.mat");
  try {
    RunMonteCarlo(plan(moved, 6), Quiet(out, 1));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("steps"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find("data_dir"), std::string::npos) << e.what();
  }
  // A changed byte is other data.
  std::string bytes = ReadTextFile(mat);
  bytes[10] = static_cast<char>(bytes[10] ^ 1);  // in the descriptive header text
  WriteFileAtomically(mat, bytes);
  try {
    RunMonteCarlo(plan(), Quiet(out, 1));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("data_files"), std::string::npos) << e.what();
  }
}

// A folder whose only run failed before computing anything (its data file damaged) holds no
// result: the corrected rerun is accepted and its config.json replaces the failed one's.
TEST(MonteCarlo, AFolderWithOnlyFailedRunsAcceptsTheCorrectedRerun) {
  const fs::path root = datasets::testing::FreshTestDir();
  const auto plan = [&](const fs::path& data) {
    MonteCarloPlan p = OdometryPlan("generated", 5, {1});
    ScenarioOptions options;
    options.steps = 5;
    options.data_dir = data.string();
    p.scenario = MakeScenarioSource("paper-synthetic", options);
    return p;
  };
  const fs::path out = root / "out";
  const fs::path damaged = root / "damaged";
  fs::create_directories(damaged / "phdslam3-synthetic");
  WriteFileAtomically(damaged / "phdslam3-synthetic" / "Environment_SLAM.mat", "MATLAB 5.0");
  try {
    RunMonteCarlo(plan(damaged), Quiet(out, 1));
  } catch (const std::exception&) {
  }
  ASSERT_TRUE(fs::exists(out / kConfigFile));
  ASSERT_FALSE(fs::exists(RunFolder(out, "odometry", 1, 1) / kMetricsFile));
  EXPECT_EQ(RunMonteCarlo(plan(datasets::testing::SyntheticDataDir()), Quiet(out, 1)).finished, 1u);
  EXPECT_FALSE(fs::exists(RunFolder(out, "odometry", 1, 1) / kErrorFile));
  EXPECT_TRUE(fs::exists(RunFolder(out, "odometry", 1, 1) / kMetricsFile));
  // With a finished run in it, the folder refuses other settings again.
  MonteCarloPlan other = plan(datasets::testing::SyntheticDataDir());
  other.experiment = "another";
  EXPECT_THROW(RunMonteCarlo(other, Quiet(out, 1)), std::invalid_argument);
}

TEST(MonteCarlo, ASecondWriterOfAFolderIsRefused) {
  const fs::path out = datasets::testing::FreshTestDir();
  {
    const ResultsLock held(out);
    EXPECT_TRUE(fs::exists(out / kLockFile));
    try {
      RunMonteCarlo(OdometryPlan("generated", 5, {1}), Quiet(out, 1));
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("in use by another phdslam process"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_FALSE(fs::exists(out / kLockFile));
  EXPECT_EQ(RunMonteCarlo(OdometryPlan("generated", 5, {1}), Quiet(out, 1)).finished, 1u);
  EXPECT_FALSE(fs::exists(out / kLockFile));
}

TEST(MonteCarlo, RejectsBadPlansBeforeRunning) {
  const fs::path out = datasets::testing::FreshTestDir();
  MonteCarloPlan plan = OdometryPlan("generated", 20, {1});
  plan.particles = {10};  // odometry takes one particle
  EXPECT_THROW(RunMonteCarlo(plan, Quiet(out, 1)), std::invalid_argument);
  plan = OdometryPlan("generated", 20, {1});
  plan.estimators[0].overrides = {{"speed", 1}};
  EXPECT_THROW(RunMonteCarlo(plan, Quiet(out, 1)), std::invalid_argument);
  plan = OdometryPlan("generated", 20, {});
  EXPECT_THROW(RunMonteCarlo(plan, Quiet(out, 1)), std::invalid_argument);
  plan = OdometryPlan("generated", 20, {3, 1, 3});
  EXPECT_THROW(RunMonteCarlo(plan, Quiet(out, 1)), std::invalid_argument);
  // More runs than one folder may plan: refused before any seed is planned or run.
  std::vector<std::uint64_t> many(kMaxSeeds / 2 + 1);
  std::iota(many.begin(), many.end(), std::uint64_t{1});
  plan = OdometryPlan("generated", 20, many);
  plan.estimators.push_back(plan.estimators[0]);
  plan.estimators[1].entry.name = "odometry-copy";
  try {
    RunMonteCarlo(plan, Quiet(out, 1));
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("500001 seeds x 2 estimator and particle counts is more "
                                         "than 1000000 runs in one results folder"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(out / kRunsFolder));
  EXPECT_THROW(MakeScenarioSource("nosuch", {}), std::invalid_argument);
  ScenarioOptions bad;
  bad.detection_probability = 1.5;
  EXPECT_THROW(MakeScenarioSource("paper-synthetic", bad), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::validation
