#include "validation/runner/experiment/merge_results.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/test_temp_dir.h"
#include "validation/runner/evaluation/run_metrics.h"
#include "validation/runner/experiment/experiment_runner.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/results/results_config.h"
#include "validation/runner/testing/results_testing.h"

namespace phdslam::validation {
namespace {

namespace fs = std::filesystem;
using testing::WithoutTimingColumns;
using testing::WithoutTimingKeys;

// phd3 (N = 1 and 3, with covariances, NEES and particles) and odometry (N = 1) on a short
// generated scenario: 3 seeds x 3 groups = 9 jobs.
Experiment SmallExperiment() {
  Experiment x;
  x.name = "merge-test";
  x.scenario = "generated";
  x.estimators = {{"phd3", nlohmann::json::object(), {1, 3}},
                  {"odometry", nlohmann::json::object(), {1}}};
  x.seeds = {1, 2, 3};
  x.steps = 25;
  x.jobs = 2;
  return x;
}

ExperimentSettings Quiet(const fs::path& out, Shard shard = {}) {
  ExperimentSettings s;
  s.out = out;
  s.show_progress = false;
  s.report_failures = false;
  s.shard = shard;
  return s;
}

// Relative paths of the regular files under `root`, except timing.json.
std::set<fs::path> Files(const fs::path& root) {
  std::set<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file() && entry.path().filename() != kTimingFile) {
      files.insert(fs::relative(entry.path(), root));
    }
  }
  return files;
}

// Every file of `a` equals the one of `b`, apart from timing (timing.json, ms columns and keys)
// and the thread count in config.json.
void ExpectSameResults(const fs::path& a, const fs::path& b) {
  const std::set<fs::path> files = Files(a);
  EXPECT_EQ(files, Files(b));
  for (const fs::path& file : files) {
    const std::string ta = ReadTextFile(a / file);
    const std::string tb = ReadTextFile(b / file);
    if (file.extension() == ".csv") {
      EXPECT_EQ(WithoutTimingColumns(ta), WithoutTimingColumns(tb)) << file;
    } else if (file.filename() == kConfigFile) {
      nlohmann::json ca = nlohmann::json::parse(ta);
      nlohmann::json cb = nlohmann::json::parse(tb);
      ca.erase("jobs");
      cb.erase("jobs");
      EXPECT_EQ(ca, cb) << file;
    } else if (file.extension() == ".json") {
      EXPECT_EQ(WithoutTimingKeys(nlohmann::json::parse(ta)),
                WithoutTimingKeys(nlohmann::json::parse(tb)))
          << file;
    } else {
      EXPECT_EQ(ta, tb) << file;
    }
  }
}

TEST(MergeResults, TwoShardsMergedEqualTheUnshardedRun) {
  const fs::path base = datasets::testing::FreshTestDir();
  const Experiment x = SmallExperiment();
  RunExperiment(x, Quiet(base / "whole"));
  const ExperimentReport first = RunExperiment(x, Quiet(base / "shard1", Shard{1, 2}));
  const ExperimentReport second = RunExperiment(x, Quiet(base / "shard2", Shard{2, 2}));
  EXPECT_EQ(first.reports.at(0).planned, 5u);  // jobs 0, 2, 4, 6, 8 of 9
  EXPECT_EQ(first.reports.at(0).outside_shard, 4u);
  EXPECT_EQ(second.reports.at(0).planned, 4u);
  // Job order: seed 1 {phd3 N1, phd3 N3, odometry N1}, seed 2 {...}: job 1 = phd3 N3 seed 1.
  EXPECT_TRUE(fs::exists(RunFolder(base / "shard2", "phd3", 3, 1) / kMetricsFile));
  EXPECT_FALSE(fs::exists(RunFolder(base / "shard1", "phd3", 3, 1)));

  const MergeReport report = MergeResults(base / "merged", {base / "shard1", base / "shard2"});
  EXPECT_EQ(report.runs_copied, 9u);
  EXPECT_EQ(report.runs_already_present, 0u);
  EXPECT_EQ(report.folders, 1u);
  ExpectSameResults(base / "whole", base / "merged");
  // The summary has the NEES columns filled for phd3 N=3.
  EXPECT_NE(ReadTextFile(base / "merged" / kSummaryFile).find("nees_fraction_inside"),
            std::string::npos);
  const nlohmann::json timing = ReadJsonObject(base / "merged" / kTimingFile);
  EXPECT_EQ(timing.at("merged_from").size(), 2u);

  // Merging again adds nothing; overlapping inputs are fine when their runs agree.
  const MergeReport again =
      MergeResults(base / "merged", {base / "shard1", base / "shard2", base / "whole"});
  EXPECT_EQ(again.runs_copied, 0u);
  EXPECT_EQ(again.runs_already_present, 9u);
  ExpectSameResults(base / "whole", base / "merged");
}

// A run written by an earlier format version (version 1: before metrics.json had
// format_version; version 2: before relocalisations; version 3: before neg_log_posterior) merges
// with the same run written now; a run with other results is still refused.
TEST(MergeResults, AnEarlierVersionsMetricsFileMergesWithTheSameRunWrittenNow) {
  const fs::path base = datasets::testing::FreshTestDir();
  Experiment x = SmallExperiment();
  x.estimators = {{"odometry", nlohmann::json::object(), {1}}};
  x.seeds = {1};
  RunExperiment(x, Quiet(base / "new"));
  RunExperiment(x, Quiet(base / "old"));
  const fs::path old_metrics = RunFolder(base / "old", "odometry", 1, 1) / kMetricsFile;
  nlohmann::json old = ReadJsonObject(old_metrics);
  ASSERT_EQ(old.at("format_version"), 4);
  ASSERT_TRUE(old.at("relocalisations").is_null());
  ASSERT_TRUE(old.at("neg_log_posterior").is_null());
  old["format_version"] = 3;
  old.erase("neg_log_posterior");
  WriteFileAtomically(old_metrics, JsonFileText(old));
  const MergeReport v3 = MergeResults(base / "merged-v3", {base / "new", base / "old"});
  EXPECT_EQ(v3.runs_copied, 1u);
  old["format_version"] = 2;
  old.erase("relocalisations");
  WriteFileAtomically(old_metrics, JsonFileText(old));
  // The run is in both inputs: copied from the first, compared with the second.
  const MergeReport v2 = MergeResults(base / "merged-v2", {base / "new", base / "old"});
  EXPECT_EQ(v2.runs_copied, 1u);
  old.erase("format_version");
  WriteFileAtomically(old_metrics, JsonFileText(old));
  const MergeReport report = MergeResults(base / "merged", {base / "new", base / "old"});
  EXPECT_EQ(report.runs_copied, 1u);
  EXPECT_TRUE(fs::exists(RunFolder(base / "merged", "odometry", 1, 1) / kMetricsFile));

  old["pos_err_sum_m"] = old.at("pos_err_sum_m").get<double>() + 1.0;
  WriteFileAtomically(old_metrics, JsonFileText(old));
  EXPECT_THROW(MergeResults(base / "merged2", {base / "new", base / "old"}), std::invalid_argument);
}

TEST(MergeResults, ShardedSweepsMergeValueByValue) {
  const fs::path base = datasets::testing::FreshTestDir();
  Experiment x = SmallExperiment();
  x.estimators = {{"odometry", nlohmann::json::object(), {}}};
  x.sweep = {ExperimentSweep{"pd", {0.5, 0.9}}};
  RunExperiment(x, Quiet(base / "whole"));
  for (int i = 1; i <= 3; ++i)
    RunExperiment(x, Quiet(base / ("shard" + std::to_string(i)), {i, 3}));
  const MergeReport report =
      MergeResults(base / "merged", {base / "shard1", base / "shard2", base / "shard3"});
  EXPECT_EQ(report.runs_copied, 6u);
  EXPECT_EQ(report.folders, 2u);
  ExpectSameResults(base / "whole", base / "merged");
}

TEST(MergeResults, ShardedGridsMergePointByPoint) {
  const fs::path base = datasets::testing::FreshTestDir();
  Experiment x = SmallExperiment();
  x.estimators = {{"odometry", nlohmann::json::object(), {}}};
  x.sweep = {ExperimentSweep{"pd", {0.5, 0.9}}, ExperimentSweep{"landmarks", {5, 9}}};
  RunExperiment(x, Quiet(base / "whole"));
  for (int i = 1; i <= 4; ++i)
    RunExperiment(x, Quiet(base / ("shard" + std::to_string(i)), {i, 4}));
  const MergeReport report = MergeResults(
      base / "merged", {base / "shard1", base / "shard2", base / "shard3", base / "shard4"});
  EXPECT_EQ(report.folders, 4u);
  ExpectSameResults(base / "whole", base / "merged");
  EXPECT_TRUE(fs::exists(base / "merged" / "sweep-pd-0.9-landmarks-5" / kSummaryFile));
  Experiment other = x;
  other.sweep[1].values = {5, 10};
  RunExperiment(other, Quiet(base / "other", {1, 4}));
  EXPECT_THROW(MergeResults(base / "m2", {base / "shard1", base / "other"}), std::invalid_argument);
}

TEST(MergeResults, RefusesConflictingFoldersBeforeCopying) {
  const fs::path base = datasets::testing::FreshTestDir();
  Experiment x = SmallExperiment();
  x.estimators = {{"odometry", nlohmann::json::object(), {}}};
  x.seeds = {1};
  RunExperiment(x, Quiet(base / "a"));
  Experiment other = x;
  other.seeds = {2};
  other.steps = 30;  // another scenario option
  RunExperiment(other, Quiet(base / "b"));
  try {
    MergeResults(base / "merged", {base / "a", base / "b"});
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scenario option.steps"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(base / "merged" / kRunsFolder));

  Experiment renamed = x;
  renamed.name = "another";
  renamed.seeds = {2};
  RunExperiment(renamed, Quiet(base / "c"));
  EXPECT_THROW(MergeResults(base / "merged", {base / "a", base / "c"}), std::invalid_argument);

  EXPECT_THROW(MergeResults(base / "a", {base / "a"}), std::invalid_argument);
  EXPECT_THROW(MergeResults(base / "merged", {base / "missing"}), std::invalid_argument);
  EXPECT_THROW(MergeResults(base / "merged", {}), std::invalid_argument);
  fs::create_directories(base / "empty");
  EXPECT_THROW(MergeResults(base / "merged", {base / "empty"}), std::invalid_argument);

  // The same run with other results (another build, say) is refused.
  fs::copy(base / "a", base / "d", fs::copy_options::recursive);
  const fs::path metrics = RunFolder(base / "d", "odometry", 1, 1) / kMetricsFile;
  nlohmann::json changed = ReadJsonObject(metrics);
  changed["pos_err_sum_m"] = changed["pos_err_sum_m"].get<double>() + 1.0;
  WriteFileAtomically(metrics, changed.dump());
  EXPECT_THROW(MergeResults(base / "merged", {base / "a", base / "d"}), std::invalid_argument);
  EXPECT_FALSE(fs::exists(base / "merged" / kRunsFolder));
}

// Expects MergeResults to throw std::runtime_error naming `file` (an input's file) and to leave
// no folder behind at `out`, which did not exist.
void ExpectRefusedNaming(const fs::path& out, const std::vector<fs::path>& inputs,
                         const fs::path& file, const std::string& why) {
  try {
    MergeResults(out, inputs);
    ADD_FAILURE() << "no error for " << why;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(out)) << why;
}

TEST(MergeResults, RefusesADamagedInputFileBeforeCopyingNamingIt) {
  const fs::path base = datasets::testing::FreshTestDir();
  Experiment x = SmallExperiment();
  x.estimators = {{"odometry", nlohmann::json::object(), {}}};
  x.seeds = {1, 2};
  RunExperiment(x, Quiet(base / "a"));
  const fs::path run = RunFolder(base / "a", "odometry", 1, 2);
  const std::string metrics = ReadTextFile(run / kMetricsFile);
  const std::string steps = ReadTextFile(run / kStepsFile);

  WriteFileAtomically(run / kMetricsFile, metrics.substr(0, metrics.size() / 2));
  ExpectRefusedNaming(base / "m1", {base / "a"}, run / kMetricsFile, "not a JSON object");
  nlohmann::json newer = nlohmann::json::parse(metrics);
  newer[kFormatVersionKey] = kMetricsFormatVersion + 1;
  WriteFileAtomically(run / kMetricsFile, newer.dump());
  ExpectRefusedNaming(base / "m2", {base / "a"}, run / kMetricsFile, "is unknown");
  WriteFileAtomically(run / kMetricsFile, metrics);

  const std::size_t cut = steps.find('\n', steps.size() / 2);
  WriteFileAtomically(run / kStepsFile, steps.substr(0, cut + 1));  // whole lines, too few
  ExpectRefusedNaming(base / "m3", {base / "a"}, run / kStepsFile, "cut short");
  WriteFileAtomically(run / kStepsFile, steps.substr(0, cut - 3));  // a line cut short
  ExpectRefusedNaming(base / "m4", {base / "a"}, run / kStepsFile, "cells, the header has");

  WriteFileAtomically(run / kStepsFile, steps);
  EXPECT_EQ(MergeResults(base / "m5", {base / "a"}).runs_copied, 2u);
  ExpectSameResults(base / "a", base / "m5");
}

// Every file under `root` with its content, for checking that a folder was left as it was.
std::map<fs::path, std::string> Contents(const fs::path& root) {
  std::map<fs::path, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), root)] = ReadTextFile(entry.path());
  }
  return files;
}

// The merge is staged beside the output: nothing of it is left there, whether it succeeds or
// fails, and a failure after every input file was checked (here: copying a truth file that is
// a folder) leaves an existing output as it was and no new one.
TEST(MergeResults, IsAllOrNothingStagedBesideTheOutput) {
  const fs::path base = datasets::testing::FreshTestDir();
  Experiment x = SmallExperiment();
  x.estimators = {{"odometry", nlohmann::json::object(), {}}};
  x.seeds = {1};
  RunExperiment(x, Quiet(base / "a"));
  x.seeds = {2};
  RunExperiment(x, Quiet(base / "b"));
  const fs::path truth_map = base / "b" / kTruthFolder / "seed-2" / kTruthMapFile;
  ASSERT_TRUE(fs::is_regular_file(truth_map));

  MergeResults(base / "out" / "merged", {base / "a"});
  const std::map<fs::path, std::string> before = Contents(base / "out" / "merged");
  fs::remove(truth_map);
  fs::create_directories(truth_map);
  EXPECT_THROW(MergeResults(base / "out" / "merged", {base / "b"}), std::runtime_error);
  EXPECT_EQ(Contents(base / "out" / "merged"), before);
  EXPECT_THROW(MergeResults(base / "out" / "new", {base / "b"}), std::runtime_error);
  EXPECT_FALSE(fs::exists(base / "out" / "new"));
  std::vector<fs::path> beside;
  for (const auto& entry : fs::directory_iterator(base / "out")) beside.push_back(entry.path());
  EXPECT_EQ(beside, std::vector<fs::path>{base / "out" / "merged"});

  fs::remove(truth_map);
  fs::copy_file(base / "a" / kTruthFolder / "seed-1" / kTruthMapFile, truth_map);
  const MergeReport report = MergeResults(base / "out" / "merged/", {base / "b"});
  EXPECT_EQ(report.runs_copied, 1u);
  EXPECT_EQ(report.runs_already_present, 0u);
  EXPECT_TRUE(fs::exists(RunFolder(base / "out" / "merged", "odometry", 1, 1) / kMetricsFile));
  EXPECT_TRUE(fs::exists(RunFolder(base / "out" / "merged", "odometry", 1, 2) / kMetricsFile));
  EXPECT_NE(ReadTextFile(base / "out" / "merged" / kSummaryFile).find("odometry,1,2,"),
            std::string::npos);
  beside.clear();
  for (const auto& entry : fs::directory_iterator(base / "out")) beside.push_back(entry.path());
  EXPECT_EQ(beside, std::vector<fs::path>{base / "out" / "merged"});
}

TEST(MergeResults, AFinishedRunReplacesAFailedOne) {
  const fs::path base = datasets::testing::FreshTestDir();
  Experiment x = SmallExperiment();
  x.estimators = {{"odometry", nlohmann::json::object(), {}}};
  x.seeds = {1, 2};
  RunExperiment(x, Quiet(base / "a"));
  fs::copy(base / "a", base / "b", fs::copy_options::recursive);
  // In "a", seed 2 failed.
  const fs::path failed = RunFolder(base / "a", "odometry", 1, 2);
  nlohmann::json error = ReadJsonObject(failed / kMetricsFile);
  error["error"] = "diverged";
  fs::remove(failed / kMetricsFile);
  WriteFileAtomically(failed / kErrorFile, error.dump());

  MergeResults(base / "only_a", {base / "a"});
  EXPECT_TRUE(fs::exists(RunFolder(base / "only_a", "odometry", 1, 2) / kErrorFile));
  EXPECT_NE(ReadTextFile(base / "only_a" / kSummaryFile).find("odometry,1,1,"), std::string::npos);

  const MergeReport report = MergeResults(base / "only_a", {base / "b"});
  EXPECT_EQ(report.runs_copied, 1u);
  EXPECT_EQ(report.runs_already_present, 1u);
  EXPECT_FALSE(fs::exists(RunFolder(base / "only_a", "odometry", 1, 2) / kErrorFile));
  ExpectSameResults(base / "b", base / "only_a");
}

}  // namespace
}  // namespace phdslam::validation
