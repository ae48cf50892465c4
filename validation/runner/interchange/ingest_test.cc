#include "validation/runner/interchange/ingest.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <string>

#include "datasets/map_io.h"
#include "datasets/test_temp_dir.h"
#include "datasets/trajectory_io.h"
#include "validation/runner/execution/monte_carlo.h"
#include "validation/runner/interchange/scenario_export.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/results/results_config.h"

namespace phdslam::validation {
namespace {

using datasets::testing::FreshTestDir;
constexpr int kSteps = 40;

ScenarioSource Source(int steps = kSteps) {
  ScenarioOptions options;
  options.steps = steps;
  return MakeScenarioSource("paper-synthetic", options);
}

// An external filter's outputs that equal the truth, shifted by `offset` metres in x.
void WritePerfectOutputs(const std::filesystem::path& from, std::uint64_t seed,
                         double offset = 0.0) {
  const datasets::Scenario s = Source().make(seed);
  const std::filesystem::path folder = from / SeedFolderName(seed);
  std::filesystem::create_directories(folder);
  std::vector<datasets::StampedPose> poses;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    Pose p = s.truth.poses[k];
    p(0) += offset;
    poses.push_back({s.StepTime(k), p});
  }
  datasets::WriteTumTrajectory(folder / kExternalTrajectoryFile, poses);
  std::vector<datasets::MapPoint> map;
  for (const Landmark& m : s.truth.landmarks) map.push_back({m, 1.0, Mat2::Identity()});
  datasets::WriteMapCsv(folder / kExternalMapFile, map);
  std::ofstream cov(folder / kExternalPoseCovFile);
  cov << "step,pxx,pxy,pxt,pyy,pyt,ptt\n";
  for (std::size_t k = 0; k < s.steps.size(); ++k) cov << k << ",1,0,0,1,0,0.01\n";
  std::ofstream timing(folder / kExternalTimingFile);
  timing << "step,ms\n";
  for (std::size_t k = 0; k < s.steps.size(); ++k) timing << k << ",0.5\n";
}

IngestRequest Request(const std::filesystem::path& from, std::vector<std::uint64_t> seeds) {
  IngestRequest r;
  r.from = from;
  r.estimator = "external-test";
  r.scenario = Source();
  r.seeds = std::move(seeds);
  return r;
}

// The message of the std::exception `f` throws, or "" when it throws none.
template <class F>
std::string ErrorOf(F f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(Ingest, PerfectOutputsScoreZeroAndJoinARunFolder) {
  const std::filesystem::path dir = FreshTestDir();
  const std::filesystem::path out = dir / "results";
  MonteCarloPlan plan;
  plan.scenario = Source();
  plan.estimators = {{FindEstimator("odometry")}};
  plan.particles = {1};
  plan.seeds = {1, 2};
  MonteCarloSettings settings;
  settings.out = out;
  settings.jobs = 1;
  settings.show_progress = false;
  RunMonteCarlo(plan, settings);

  WritePerfectOutputs(dir / "from", 1);
  WritePerfectOutputs(dir / "from", 2, 3.0);
  const IngestReport report = IngestResults(Request(dir / "from", {1, 2}), out);
  EXPECT_EQ(report.runs, 2U);

  const nlohmann::json m1 = ReadJsonObject(RunFolder(out, "external-test", 1, 1) / kMetricsFile);
  EXPECT_EQ(m1.at("pos_rmse_m").get<double>(), 0.0);
  EXPECT_EQ(m1.at("gospa_m").get<double>(), 0.0);
  EXPECT_EQ(m1.at("steps").get<int>(), kSteps);
  EXPECT_EQ(m1.at("pose_nees_count").get<int>(), kSteps);
  EXPECT_DOUBLE_EQ(m1.at("ms_total").get<double>(), 0.5 * kSteps);
  const nlohmann::json m2 = ReadJsonObject(RunFolder(out, "external-test", 1, 2) / kMetricsFile);
  EXPECT_NEAR(m2.at("pos_rmse_m").get<double>(), 3.0, 1e-9);
  // The NEES of a 3 m error with unit variance is 9 at every step.
  EXPECT_NEAR(m2.at("pose_nees_mean").get<double>(), 9.0, 1e-6);

  const CsvTable summary = ReadCsvFile(out / kSummaryFile);
  ASSERT_EQ(summary.rows.size(), 2U);
  EXPECT_EQ(summary.rows[0][0], "external-test");
  EXPECT_EQ(summary.rows[1][0], "odometry");
  const CsvTable runs = ReadCsvFile(out / kRunsTableFile);
  EXPECT_EQ(runs.rows.size(), 4U);
  const nlohmann::json config = ReadJsonObject(out / kConfigFile);
  EXPECT_TRUE(config.at("estimators").contains("odometry"));
  EXPECT_TRUE(config.at("estimators").contains("external-test"));
  EXPECT_TRUE(config.contains("jobs"));  // kept from the run's config.json
  for (const char* file : {kStepsFile, kTrajectoryFile, kMapFile}) {
    EXPECT_TRUE(std::filesystem::exists(RunFolder(out, "external-test", 1, 1) / file)) << file;
  }
}

TEST(Ingest, RefusesAFolderOfOtherScenarioOptions) {
  const std::filesystem::path dir = FreshTestDir();
  WritePerfectOutputs(dir / "from", 1);
  IngestResults(Request(dir / "from", {1}), dir / "results");
  IngestRequest other = Request(dir / "from", {1});
  other.experiment = "another";
  EXPECT_THROW(IngestResults(other, dir / "results"), std::invalid_argument);
}

TEST(Ingest, MissingSeedNamesTheFolderAndWritesNothing) {
  const std::filesystem::path dir = FreshTestDir();
  WritePerfectOutputs(dir / "from", 1);
  const std::string e = ErrorOf([&] { IngestResults(Request(dir / "from", {1, 2}), dir / "r"); });
  EXPECT_NE(e.find("seed-2: missing"), std::string::npos) << e;
  EXPECT_FALSE(std::filesystem::exists(dir / "r" / kSummaryFile));
}

TEST(Ingest, WrongStepCountNamesTheFile) {
  const std::filesystem::path dir = FreshTestDir();
  WritePerfectOutputs(dir / "from", 1);
  IngestRequest r = Request(dir / "from", {1});
  r.scenario = Source(kSteps + 1);
  const std::string e = ErrorOf([&] { IngestResults(r, dir / "r"); });
  EXPECT_NE(e.find("trajectory.tum: 40 poses, the scenario has 41 steps"), std::string::npos) << e;
}

TEST(Ingest, BadValuesNameFileAndLine) {
  const std::filesystem::path dir = FreshTestDir();
  WritePerfectOutputs(dir / "from", 1);
  const std::filesystem::path seed = dir / "from" / "seed-1";
  std::ofstream(seed / kExternalPoseCovFile) << "step,pxx,pxy,pxt,pyy,pyt,ptt\n0,1,0,0,nan,0,1\n";
  std::string e = ErrorOf([&] { IngestResults(Request(dir / "from", {1}), dir / "r"); });
  EXPECT_NE(e.find("pose_cov.csv:2: column 'pyy': 'nan' is not a finite number"), std::string::npos)
      << e;
  std::ofstream(seed / kExternalPoseCovFile) << "step,pxx,pxy,pxt,pyy,pyt,ptt\n40,1,0,0,1,0,1\n";
  e = ErrorOf([&] { IngestResults(Request(dir / "from", {1}), dir / "r"); });
  EXPECT_NE(e.find("pose_cov.csv:2: step 40 is not an integer in [0, 40)"), std::string::npos) << e;
  std::filesystem::remove(seed / kExternalPoseCovFile);
  std::ofstream(seed / kExternalTimingFile) << "step,ms\n0,1\n";
  e = ErrorOf([&] { IngestResults(Request(dir / "from", {1}), dir / "r"); });
  EXPECT_NE(e.find("timing.csv: no row for step 1"), std::string::npos) << e;
  std::filesystem::remove(seed / kExternalTimingFile);
  std::ofstream(seed / kExternalMapFile) << "x,y\n1,2\n3,nan\n";
  e = ErrorOf([&] { IngestResults(Request(dir / "from", {1}), dir / "r"); });
  EXPECT_NE(e.find("map.csv:3"), std::string::npos) << e;
  std::ofstream(seed / kExternalMapFile) << "x,y\n1,2\n";
  std::ofstream(seed / kExternalAssociationFile) << "step,index,x,y\n3,99,1,2\n";
  e = ErrorOf([&] { IngestResults(Request(dir / "from", {1}), dir / "r"); });
  EXPECT_NE(e.find("association.csv:2: index 99 is not an integer"), std::string::npos) << e;
  std::filesystem::remove(seed / kExternalAssociationFile);
  std::ofstream(seed / kExternalTrajectoryFile) << "# t x y z qx qy qz qw\n0 1 2 0 0 0 0 1\n";
  e = ErrorOf([&] { IngestResults(Request(dir / "from", {1}), dir / "r"); });
  EXPECT_NE(e.find("trajectory.tum: 1 poses, the scenario has 40 steps"), std::string::npos) << e;
  EXPECT_FALSE(std::filesystem::exists(dir / "r" / kSummaryFile));
}

TEST(Ingest, ShiftedTimeStampNamesTheLine) {
  const std::filesystem::path dir = FreshTestDir();
  WritePerfectOutputs(dir / "from", 1);
  const datasets::Scenario s = Source().make(1);
  std::vector<datasets::StampedPose> poses;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    poses.push_back({s.StepTime(k) + (k == 5 ? 0.5 : 0.0), s.truth.poses[k]});
  }
  datasets::WriteTumTrajectory(dir / "from/seed-1" / kExternalTrajectoryFile, poses);
  const std::string e = ErrorOf([&] { IngestResults(Request(dir / "from", {1}), dir / "r"); });
  EXPECT_NE(e.find("trajectory.tum:7: time stamp 5.5 of pose 5"), std::string::npos) << e;
}

TEST(Ingest, AssociationsAreScored) {
  const std::filesystem::path dir = FreshTestDir();
  WritePerfectOutputs(dir / "from", 1);
  const datasets::Scenario s = Source().make(1);
  // Every measurement associated with its true landmark (the oracle's association).
  std::ofstream a(dir / "from/seed-1" / kExternalAssociationFile);
  a << "step,index,x,y\n";
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    for (std::size_t i = 0; i < s.steps[k].origin.size(); ++i) {
      const int o = s.steps[k].origin[i];
      if (o < 0) continue;
      const Landmark& m = s.truth.landmarks[static_cast<std::size_t>(o)];
      a << k << "," << i << "," << m(0) << "," << m(1) << "\n";
    }
  }
  a.close();
  IngestResults(Request(dir / "from", {1}), dir / "r");
  const nlohmann::json m =
      ReadJsonObject(RunFolder(dir / "r", "external-test", 1, 1) / kMetricsFile);
  EXPECT_EQ(m.at("da_tpr").get<double>(), 1.0);
  EXPECT_EQ(m.at("da_tnr").get<double>(), 1.0);
}

TEST(Ingest, ExportChecksumsMustMatchTheRebuiltScenario) {
  const std::filesystem::path dir = FreshTestDir();
  WritePerfectOutputs(dir / "from", 1);
  const ScenarioSource source = Source();
  ExportDescription d;
  d.scenario = source.name;
  d.options = source.options;
  d.seeds = {1};
  WriteExport(dir / "export", d, {source.make(1)});
  IngestRequest r = Request(dir / "from", {1});
  r.export_dir = dir / "export";
  EXPECT_EQ(IngestResults(r, dir / "r").runs, 1U);
  // A scenario rebuilt with other options differs from the export.
  r.scenario = Source(kSteps - 1);
  std::string e = ErrorOf([&] { IngestResults(r, dir / "r2"); });
  EXPECT_NE(e.find("differs from the exported one"), std::string::npos) << e;
  // A file edited after export no longer has its SHA256SUMS checksum.
  r.scenario = Source();
  std::ofstream(dir / "export/seed-1/measurements.csv", std::ios::app) << "39,99,1,1\n";
  e = ErrorOf([&] { IngestResults(r, dir / "r3"); });
  EXPECT_NE(e.find("measurements.csv: its SHA-256 differs from"), std::string::npos) << e;
  EXPECT_FALSE(std::filesystem::exists(dir / "r3" / kSummaryFile));
  // An export is written into a new or empty folder only.
  e = ErrorOf([&] { WriteExport(dir / "export", d, {source.make(1)}); });
  EXPECT_NE(e.find("is not empty"), std::string::npos) << e;
}

// The files of a folder and their contents, to compare a folder before and after a command.
std::map<std::string, std::string> FolderContents(const std::filesystem::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file()) {
      files[entry.path().lexically_relative(folder).string()] = ReadTextFile(entry.path());
    }
  }
  return files;
}

TEST(Ingest, AnEstimatorWithRunsIsReplacedOnlyWhenAsked) {
  const std::filesystem::path dir = FreshTestDir();
  WritePerfectOutputs(dir / "from", 1);
  WritePerfectOutputs(dir / "from", 2);
  EXPECT_EQ(IngestResults(Request(dir / "from", {1, 2}), dir / "r").runs, 2U);
  const auto before = FolderContents(dir / "r");
  const std::string e = ErrorOf([&] { IngestResults(Request(dir / "from", {1}), dir / "r"); });
  EXPECT_NE(e.find("already holds 2 runs of estimator 'external-test'"), std::string::npos) << e;
  EXPECT_NE(e.find("--replace"), std::string::npos) << e;
  EXPECT_EQ(FolderContents(dir / "r"), before);
  IngestRequest r = Request(dir / "from", {1});
  r.replace = true;
  const IngestReport report = IngestResults(r, dir / "r");
  ASSERT_EQ(report.replaced.size(), 2U);
  EXPECT_EQ(report.replaced[0], RunFolder(dir / "r", "external-test", 1, 1));
  EXPECT_TRUE(std::filesystem::exists(RunFolder(dir / "r", "external-test", 1, 1) / kMetricsFile));
  EXPECT_FALSE(std::filesystem::exists(RunFolder(dir / "r", "external-test", 1, 2)));
  EXPECT_FALSE(std::filesystem::exists(dir / "r" / kIngestStagingFolder));
}

TEST(Ingest, AFailingValueLeavesTheResultsFolderAsItWas) {
  const std::filesystem::path dir = FreshTestDir();
  WritePerfectOutputs(dir / "from", 1);
  EXPECT_EQ(IngestResults(Request(dir / "from", {1}), dir / "r").runs, 1U);
  const auto before = FolderContents(dir / "r");
  IngestRequest r = Request(dir / "from", {1});
  r.estimator = "second";
  const std::filesystem::path seed = dir / "from" / "seed-1";
  const auto refused = [&](const std::string& file, const std::string& text,
                           const std::string& expected) {
    std::ofstream(seed / file) << text;
    const std::string e = ErrorOf([&] { IngestResults(r, dir / "r"); });
    EXPECT_NE(e.find(expected), std::string::npos) << e;
    EXPECT_EQ(FolderContents(dir / "r"), before) << file;
  };
  std::string timing = "step,ms\n";
  for (int k = 1; k < kSteps; ++k) timing += std::to_string(k) + ",1\n";
  refused(kExternalTimingFile, timing + "0,1e300\n",
          "timing.csv:41: column 'ms': 1e+300 is beyond +-1e+09");
  std::filesystem::remove(seed / kExternalTimingFile);
  refused(kExternalPoseCovFile, "step,pxx,pxy,pxt,pyy,pyt,ptt\n0,1,0,0,-2,0,1\n",
          "pose_cov.csv:2: column 'pyy': the variance -2 is negative");
  refused(kExternalPoseCovFile, "step,pxx,pxy,pxt,pyy,pyt,ptt\n0,1,2,0,1,0,1\n",
          "pose_cov.csv:2: columns 'pxy', 'pxt', 'pyt': the covariance is not positive");
  std::filesystem::remove(seed / kExternalPoseCovFile);
  refused(kExternalMapFile, "x,y,weight\n1,2,-5\n", "map.csv:2: column 'weight' (field 3): -5");
  refused(kExternalMapFile, "x,y,weight\n1,2,1.5\n", "is outside [0, 1]");
}

TEST(Ingest, RejectsRegisteredNames) {
  const std::filesystem::path dir = FreshTestDir();
  WritePerfectOutputs(dir / "from", 1);
  IngestRequest r = Request(dir / "from", {1});
  r.estimator = "phd3";
  EXPECT_THROW(IngestResults(r, dir / "r"), std::invalid_argument);
  r.estimator = "a/b";
  EXPECT_THROW(IngestResults(r, dir / "r"), std::invalid_argument);
}

}  // namespace
}  // namespace phdslam::validation
