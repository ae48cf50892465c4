#include "validation/runner/experiment/option_precedence.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "datasets/test_temp_dir.h"
#include "validation/runner/experiment/experiment_assignments.h"
#include "validation/runner/io/results_io.h"

namespace phdslam::validation {
namespace {

std::string ErrorOf(const ExperimentOptions& options) {
  try {
    ResolveExperiment(options);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// An experiment file with a `set` and a `particles` list for phd3 and every key --experiment
// options can override.
std::string WriteExperimentFile() {
  const std::filesystem::path path = datasets::testing::FreshTestDir() / "file-exp.yaml";
  WriteFileAtomically(path, R"(scenario: paper-synthetic
estimators:
  - {name: phd3, set: {resampling: false}, particles: [1, 5]}
  - phd1
particles: [1, 10]
seeds: 1-3
steps: 40
scenario_options: {pd: 0.8, clutter_rate: 2}
)");
  return path.string();
}

TEST(OptionPrecedence, WithoutAFileScenarioEstimatorAndSeedsAreRequired) {
  ExperimentOptions o;
  EXPECT_EQ(ErrorOf(o), "run: --scenario is required (or give --experiment)");
  o.given["--scenario"] = "generated";
  EXPECT_EQ(ErrorOf(o), "run: --estimator is required (or give --experiment)");
  o.given["--estimator"] = "odometry,phd3";
  EXPECT_EQ(ErrorOf(o), "run: --seeds is required (or give --experiment)");
  o.given["--seeds"] = "2,4-5";
  const Experiment x = ResolveExperiment(o);
  EXPECT_EQ(x.scenario, "generated");
  ASSERT_EQ(x.estimators.size(), 2u);
  EXPECT_EQ(x.estimators[1].name, "phd3");
  EXPECT_EQ(x.seeds, (std::vector<std::uint64_t>{2, 4, 5}));
  EXPECT_EQ(x.particles, (std::vector<int>{1}));
  EXPECT_EQ(x.name, "default");
  EXPECT_TRUE(x.source.is_null());  // nothing to record without a file
}

TEST(OptionPrecedence, TheFileGivesEveryValueNoOptionGives) {
  ExperimentOptions o;
  o.file = WriteExperimentFile();
  const Experiment x = ResolveExperiment(o);
  EXPECT_EQ(x.name, "file-exp");
  EXPECT_EQ(x.scenario, "paper-synthetic");
  EXPECT_EQ(x.particles, (std::vector<int>{1, 10}));
  EXPECT_EQ(x.steps, 40);
  EXPECT_EQ(x.pd, 0.8);
  EXPECT_EQ(x.clutter_rate, 2.0);
  EXPECT_EQ(x.source.at("command_line"), nlohmann::json::array());
}

TEST(OptionPrecedence, EveryGivenOptionWinsAndIsRecordedInOrder) {
  ExperimentOptions o;
  o.file = WriteExperimentFile();
  o.given = {{"--scenario", "generated"},
             {"--particles", "3"},
             {"--seeds", "7"},
             {"--steps", 12},
             {"--jobs", 1},
             {"--experiment-name", "other"},
             {"--pd", 0.5},
             {"--clutter-rate", 4.0},
             {"--data-dir", "/data"},
             {"--set", {"phd1:resampling=true"}},
             {"--scenario-set", {"clutter_rate=6"}}};
  const Experiment x = ResolveExperiment(o);
  EXPECT_EQ(x.scenario, "generated");
  EXPECT_EQ(x.particles, (std::vector<int>{3}));
  EXPECT_EQ(x.seeds, (std::vector<std::uint64_t>{7}));
  EXPECT_EQ(x.steps, 12);
  EXPECT_EQ(x.jobs, 1);
  EXPECT_EQ(x.name, "other");
  EXPECT_EQ(x.pd, 0.5);
  EXPECT_EQ(x.clutter_rate, 6.0);  // --scenario-set applies after --clutter-rate
  EXPECT_EQ(x.data_dir, "/data");
  EXPECT_EQ(x.estimators[1].overrides, (nlohmann::json{{"resampling", true}}));
  // --data-dir is a machine setting: not recorded as overriding the file.
  EXPECT_EQ(
      x.source.at("command_line"),
      (nlohmann::json{"--scenario", "--particles", "--seeds", "--steps", "--jobs",
                      "--experiment-name", "--pd", "--clutter-rate", "--set", "--scenario-set"}));
}

TEST(OptionPrecedence, EstimatorSelectsAndKeepsTheFilesSettingsOfThoseItNames) {
  ExperimentOptions o;
  o.file = WriteExperimentFile();
  o.given["--estimator"] = "phd3,odometry";
  const Experiment x = ResolveExperiment(o);
  ASSERT_EQ(x.estimators.size(), 2u);
  EXPECT_EQ(x.estimators[0].name, "phd3");
  EXPECT_EQ(x.estimators[0].overrides, (nlohmann::json{{"resampling", false}}));
  EXPECT_EQ(x.estimators[0].particles, (std::vector<int>{1, 5}));
  EXPECT_EQ(x.estimators[1].name, "odometry");
  EXPECT_EQ(x.estimators[1].overrides, nlohmann::json::object());
  EXPECT_TRUE(x.estimators[1].particles.empty());
  EXPECT_EQ(x.source.at("command_line"), (nlohmann::json{"--estimator"}));
}

TEST(OptionPrecedence, SetMergesIntoTheFilesSetAndNamesAnUnknownEstimator) {
  Experiment x;
  x.estimators = {{"phd3", {{"map", {{"merge_threshold", 4}}}}}, {"phd1"}};
  ApplyParameterAssignments({"phd3:map.prune_threshold=0.001", "resampling=false"}, x);
  EXPECT_EQ(x.estimators[0].overrides,
            (nlohmann::json{{"map", {{"merge_threshold", 4}, {"prune_threshold", 0.001}}},
                            {"resampling", false}}));
  EXPECT_EQ(x.estimators[1].overrides, (nlohmann::json{{"resampling", false}}));
  try {
    ApplyParameterAssignments({"glmb2:x=1"}, x);
    ADD_FAILURE() << "no error for an estimator not in the experiment";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "--set 'glmb2:x=1': estimator 'glmb2' is not among the experiment's estimators");
  }
}

TEST(OptionPrecedence, ScenarioSetTakesOneKeyAndNamesTheAssignment) {
  Experiment x;
  ApplyScenarioAssignments({"pd=0.7", "landmarks=30"}, x);
  EXPECT_EQ(x.pd, 0.7);
  EXPECT_EQ(x.scenario_settings, (nlohmann::json{{"landmarks", 30}}));
  for (const std::string bad : {"phd3:pd=0.5", "map.x=1"}) {
    try {
      ApplyScenarioAssignments({bad}, x);
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), "--scenario-set '" + bad + "': expected key=value");
    }
  }
  try {
    ApplyScenarioAssignments({"pd=high"}, x);
    ADD_FAILURE() << "no error for a non-number pd";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--scenario-set 'pd=high': ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace phdslam::validation
