#include "validation/runner/experiment/experiment_keys.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>

#include "datasets/test_temp_dir.h"
#include "validation/runner/experiment/option_precedence.h"
#include "validation/runner/io/results_io.h"

namespace phdslam::validation {
namespace {

TEST(ExperimentKeys, EveryRowCanBeReadWhereverItIsNamed) {
  std::set<std::string> file_keys;
  std::set<std::string> options;
  std::set<std::string> manifest_keys;
  for (const ExperimentKey& key : ExperimentKeys()) {
    const std::string name = key.file_key + "/" + key.option;
    EXPECT_FALSE(key.file_key.empty() && key.option.empty()) << "a row without a name";
    if (!key.file_key.empty()) {
      EXPECT_TRUE(key.read_file) << name;
      EXPECT_TRUE(file_keys.insert(key.file_key).second) << name << ": file key twice";
    }
    if (!key.option.empty()) {
      EXPECT_TRUE(key.apply_option) << name;
      EXPECT_FALSE(key.help.empty()) << name;
      EXPECT_EQ(key.option.rfind("--", 0), 0u) << name;
      EXPECT_TRUE(options.insert(key.option).second) << name << ": option twice";
      EXPECT_EQ(FindExperimentOption(key.option), &key) << name;
    }
    if (!key.manifest_key.empty()) {
      EXPECT_TRUE(key.write_manifest && key.read_manifest) << name;
      EXPECT_TRUE(key.export_option)
          << name << ": the manifest records the scenario's options only";
      EXPECT_TRUE(manifest_keys.insert(key.manifest_key).second) << name;
    }
    // A required key is required in files and (without a file) on the command line.
    EXPECT_TRUE(!key.required || (!key.file_key.empty() && !key.option.empty())) << name;
    EXPECT_TRUE(!key.machine_setting || key.file_key.empty()) << name << ": read from files";
  }
  EXPECT_EQ(FindExperimentOption("--out"), nullptr);
}

// Every key that is both a file key and an option gives the same experiment either way.
TEST(ExperimentKeys, AFileKeyAndItsOptionGiveTheSameExperiment) {
  const std::filesystem::path path = datasets::testing::FreshTestDir() / "keys.yaml";
  WriteFileAtomically(path, R"(name: other
scenario: generated
estimators: [odometry, phd3]
particles: [3, 7]
seeds: 4-5
steps: 12
jobs: 1
scenario_options: {landmarks: 30, pd: 0.7}
map_ospa: true
map_ospa_cutoff: 0.5
)");
  ExperimentOptions from_file;
  from_file.file = path.string();
  ExperimentOptions from_options;
  from_options.given = {{"--experiment-name", "other"},
                        {"--scenario", "generated"},
                        {"--estimator", "odometry,phd3"},
                        {"--particles", "3,7"},
                        {"--seeds", "4-5"},
                        {"--steps", 12},
                        {"--jobs", 1},
                        {"--scenario-set", {"landmarks=30", "pd=0.7"}},
                        {"--map-ospa", true},
                        {"--map-ospa-cutoff", 0.5}};
  const Experiment a = ResolveExperiment(from_file);
  const Experiment b = ResolveExperiment(from_options);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.scenario, b.scenario);
  ASSERT_EQ(a.estimators.size(), b.estimators.size());
  for (std::size_t i = 0; i < a.estimators.size(); ++i) {
    EXPECT_EQ(a.estimators[i].name, b.estimators[i].name);
  }
  EXPECT_EQ(a.particles, b.particles);
  EXPECT_EQ(a.seeds, b.seeds);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.jobs, b.jobs);
  EXPECT_EQ(a.pd, b.pd);
  EXPECT_EQ(a.scenario_settings, b.scenario_settings);
  EXPECT_EQ(a.map_ospa, b.map_ospa);
  EXPECT_EQ(a.map_ospa_cutoff, b.map_ospa_cutoff);
  EXPECT_EQ(a.map_ospa_cutoff, 0.5);
}

TEST(ExperimentKeys, TheManifestRowsReadBackWhatTheyWrite) {
  Experiment x;
  x.steps = 30;
  x.pd = 0.9;
  x.scenario_settings = {{"landmarks", 40}};
  nlohmann::json request = nlohmann::json::object();
  for (const ExperimentKey& key : ExperimentKeys()) {
    if (!key.manifest_key.empty()) request[key.manifest_key] = key.write_manifest(x);
  }
  EXPECT_EQ(request, (nlohmann::json{{"steps", 30},
                                     {"pd", 0.9},
                                     {"clutter_rate", nullptr},
                                     {"settings", {{"landmarks", 40}}}}));
  Experiment back;
  back.clutter_rate = 3.0;  // null in the manifest: not set
  for (const ExperimentKey& key : ExperimentKeys()) {
    if (!key.manifest_key.empty()) key.read_manifest(request.at(key.manifest_key), back);
  }
  EXPECT_EQ(back.steps, 30);
  EXPECT_EQ(back.pd, 0.9);
  EXPECT_FALSE(back.clutter_rate.has_value());
  EXPECT_EQ(back.scenario_settings, x.scenario_settings);
}

TEST(ExperimentKeys, AnOptionNoKeyHasIsRefusedAndMachineSettingsAreNotRecorded) {
  Experiment x;
  try {
    ApplyGivenOptions({{"--out", "somewhere"}}, x);
    ADD_FAILURE() << "no error for --out";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "--out is not an option of an experiment");
  }
  const std::vector<std::string> applied =
      ApplyGivenOptions({{"--data-dir", "/data"}, {"--steps", 3}}, x);
  EXPECT_EQ(applied, std::vector<std::string>{"--steps"});
  EXPECT_EQ(x.data_dir, "/data");
  EXPECT_EQ(x.steps, 3);
}

}  // namespace
}  // namespace phdslam::validation
