#include "validation/runner/experiment/experiment_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "datasets/test_temp_dir.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/yaml_shape.h"

namespace phdslam::validation {
namespace {

// The message of the std::invalid_argument `parse` throws ("" when it throws nothing).
template <typename F>
std::string ErrorOf(F parse) {
  try {
    parse();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// The message of any exception reading the experiment file `path` throws ("" when none).
std::string ReadError(const std::filesystem::path& path) {
  try {
    ReadExperimentFile(path);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

std::string ParseError(const std::string& text) {
  return ErrorOf([&] { ParseExperimentYaml(text, "exp.yaml", "exp"); });
}

TEST(ExperimentFile, ReadsEveryKey) {
  const Experiment x = ParseExperimentYaml(R"(
name: table2-check
scenario: paper-synthetic
estimators:
  - phd3
  - {name: phd1, set: {resampling: false, map: {merge_threshold: 10}}}
  - name: odometry
    particles: [1]
particles: [1, 10, 100]
seeds: 1-5
steps: 300
scenario_options: {pd: 0.8, clutter_rate: 2}
jobs: 2
)",
                                           "exp.yaml", "exp");
  EXPECT_EQ(x.name, "table2-check");
  EXPECT_EQ(x.scenario, "paper-synthetic");
  ASSERT_EQ(x.estimators.size(), 3u);
  EXPECT_EQ(x.estimators[0].name, "phd3");
  EXPECT_EQ(x.estimators[0].overrides, nlohmann::json::object());
  EXPECT_TRUE(x.estimators[0].particles.empty());
  EXPECT_EQ(x.estimators[1].name, "phd1");
  EXPECT_EQ(x.estimators[1].overrides,
            (nlohmann::json{{"resampling", false}, {"map", {{"merge_threshold", 10}}}}));
  EXPECT_EQ(x.estimators[2].particles, std::vector<int>({1}));
  EXPECT_EQ(x.particles, std::vector<int>({1, 10, 100}));
  EXPECT_EQ(x.seeds, std::vector<std::uint64_t>({1, 2, 3, 4, 5}));
  EXPECT_EQ(x.steps, 300);
  EXPECT_EQ(x.pd, 0.8);
  EXPECT_EQ(x.clutter_rate, 2.0);
  EXPECT_EQ(x.jobs, 2);
  EXPECT_TRUE(x.sweep.empty());
  EXPECT_FALSE(x.data_dir.has_value());
  EXPECT_EQ(x.source.at("path"), "exp.yaml");
  EXPECT_EQ(x.source.at("values").at("particles"), nlohmann::json({1, 10, 100}));
  EXPECT_NE(x.source.at("text").get<std::string>().find("table2-check"), std::string::npos);
}

TEST(ExperimentFile, ReadsOneBoundedRegularFile) {
  const std::string good = "scenario: s\nestimators: [a]\nseeds: 1\n";
  EXPECT_NE(ErrorOf([&] {
              ParseExperimentYaml(good + "---\n" + good, "exp.yaml", "exp");
            }).find("exp.yaml:4: a second YAML document"),
            std::string::npos);
  EXPECT_NE(ReadError("/dev/zero").find("/dev/zero: not a regular file"), std::string::npos);
  const std::filesystem::path big = datasets::testing::FreshTestDir() / "big.yaml";
  WriteFileAtomically(big, std::string(kMaxExperimentFileBytes + 1, '#'));
  EXPECT_NE(ReadError(big).find("bytes, more than the 1048576"), std::string::npos);
}

TEST(ExperimentFile, DefaultsAndSeedForms) {
  const Experiment x = ParseExperimentYaml(
      "scenario: generated\nestimators: [odometry]\nseeds: [1, 3, 10-12]\n", "f.yaml", "stem");
  EXPECT_EQ(x.name, "stem");
  EXPECT_EQ(x.particles, std::vector<int>({1}));
  EXPECT_EQ(x.seeds, std::vector<std::uint64_t>({1, 3, 10, 11, 12}));
  EXPECT_EQ(x.steps, 0);
  EXPECT_FALSE(x.pd.has_value());
  EXPECT_FALSE(x.jobs.has_value());
  EXPECT_EQ(ParseExperimentYaml("scenario: s\nestimators: [a]\nseeds: 7\n", "f", "n").seeds,
            std::vector<std::uint64_t>({7}));
}

TEST(ExperimentFile, SetValuesAreTypedLikeCommandLineValues) {
  const Experiment x = ParseExperimentYaml(R"(
scenario: s
seeds: 1
estimators:
  - name: e
    set: {i: 3, d: 0.5, b: true, s: text, q: "12", n: ~, l: [1, 2], e: 1e-3}
)",
                                           "f", "n");
  const nlohmann::json& o = x.estimators[0].overrides;
  EXPECT_TRUE(o.at("i").is_number_integer());
  EXPECT_EQ(o.at("d"), 0.5);
  EXPECT_EQ(o.at("b"), true);
  EXPECT_EQ(o.at("s"), "text");
  EXPECT_EQ(o.at("q"), "12");  // quoted: a string
  EXPECT_TRUE(o.at("n").is_null());
  EXPECT_EQ(o.at("l"), nlohmann::json({1, 2}));
  EXPECT_EQ(o.at("e"), 1e-3);
}

TEST(ExperimentFile, ReadsASweep) {
  const Experiment x = ParseExperimentYaml(
      "scenario: s\nestimators: [e]\nseeds: 1-2\nsweep: {parameter: clutter_rate, values: [0, "
      "2.5, 10]}\n",
      "f", "n");
  ASSERT_EQ(x.sweep.size(), 1u);
  EXPECT_EQ(x.sweep[0].parameter, "clutter_rate");
  EXPECT_EQ(x.sweep[0].values, std::vector<nlohmann::json>({0, 2.5, 10}));
}

TEST(ExperimentFile, ReadsAGridAndScenarioOptions) {
  const Experiment x = ParseExperimentYaml(R"(
scenario: generated
estimators: [phd3]
seeds: 1-2
scenario_options: {pd: 0.8, landmarks: 40, measurement_noise_cov: [0.5, 0.001]}
sweep:
  - {parameter: clutter_rate, values: [0, 5]}
  - {parameter: "phd3:resampling", values: [true, false]}
  - {parameter: particles, values: [1, 10]}
)",
                                           "f", "n");
  EXPECT_EQ(x.pd, 0.8);
  EXPECT_EQ(x.scenario_settings,
            (nlohmann::json{{"landmarks", 40}, {"measurement_noise_cov", {0.5, 0.001}}}));
  ASSERT_EQ(x.sweep.size(), 3u);
  EXPECT_EQ(x.sweep[1].parameter, "phd3:resampling");
  EXPECT_EQ(x.sweep[1].values, std::vector<nlohmann::json>({true, false}));
  EXPECT_EQ(x.sweep[2].values, std::vector<nlohmann::json>({1, 10}));
}

TEST(ExperimentFile, UnknownKeysNameTheFileLineAndKey) {
  const std::string base = "scenario: s\nestimators: [e]\nseeds: 1\n";
  std::string e = ParseError(base + "partcles: [1]\n");
  EXPECT_NE(e.find("exp.yaml:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key 'partcles'"), std::string::npos) << e;
  EXPECT_NE(e.find("particles"), std::string::npos) << e;  // the known keys are listed
  e = ParseError("scenario: s\nseeds: 1\nestimators:\n  - {name: e, sett: {a: 1}}\n");
  EXPECT_NE(e.find("exp.yaml:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key 'sett'"), std::string::npos) << e;
  e = ParseError(base + "sweep: {parameter: pd, values: [0.5], step: 1}\n");
  EXPECT_NE(e.find("unknown key 'step'"), std::string::npos) << e;
}

TEST(ExperimentFile, DuplicateKeysAreRefusedNamingBothLines) {
  std::string e = ParseError("scenario: s\nestimators: [e]\nseeds: 1\nseeds: 2\n");
  EXPECT_NE(e.find("exp.yaml:4: the key 'seeds' appears twice"), std::string::npos) << e;
  EXPECT_NE(e.find("first on line 3"), std::string::npos) << e;
  e = ParseError("scenario: s\nseeds: 1\nestimators:\n  - name: e\n    set: {a: 1, b: 2, a: 3}\n");
  EXPECT_NE(e.find("exp.yaml:5: the key 'a' appears twice"), std::string::npos) << e;
  // The same key in two different mappings is fine.
  EXPECT_EQ(ParseError("scenario: s\nseeds: 1\nestimators:\n  - {name: e, set: {a: 1}}\n"
                       "  - {name: f, set: {a: 1}}\n"),
            "");
}

TEST(ExperimentFile, AliasesAndDeepNestingAreRefusedWithoutExpanding) {
  // Nine levels of nine aliases each: 9^9 values if expanded.
  std::string bomb = "scenario: s\nseeds: 1\nestimators:\n  - name: e\n    set:\n";
  bomb += "      a0: &a0 [x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i < 9; ++i) {
    const std::string prev = "*a" + std::to_string(i - 1);
    bomb += "      a" + std::to_string(i) + ": &a" + std::to_string(i) + " [" + prev;
    for (int j = 1; j < 9; ++j) bomb += ", " + prev;
    bomb += "]\n";
  }
  std::string e = ParseError(bomb);
  EXPECT_NE(e.find("exp.yaml:7: YAML aliases"), std::string::npos) << e;
  e = ParseError("scenario: s\nestimators: [e]\nseeds: 1\nsweep: " + std::string(100, '[') +
                 std::string(100, ']') + "\n");
  EXPECT_NE(e.find("nested deeper than"), std::string::npos) << e;
}

TEST(ExperimentFile, TextThatIsNotUtf8IsRefusedWithItsPosition) {
  // The fuzzer's finding: a sweep value with a byte that is not UTF-8 reached a JSON dump, which
  // threw nlohmann's type_error instead of std::invalid_argument.
  std::string e = ParseError(
      "scenario: s\nestimators: [e]\nseeds: 1\nsweep:\n  parameter: pd\n  values: [0.3, a\x9d]\n");
  EXPECT_NE(e.find("exp.yaml: line 6, column 18: not valid UTF-8 (byte 0x9D)"), std::string::npos)
      << e;
  // Anywhere in the file, comments included: config.json records the whole text.
  e = ParseError("# caf\xe9\nscenario: s\nestimators: [e]\nseeds: 1\n");
  EXPECT_NE(e.find("exp.yaml: line 1, column 6: not valid UTF-8 (byte 0xE9)"), std::string::npos)
      << e;
  EXPECT_EQ(ParseError("# caf\xc3\xa9\nscenario: s\nestimators: [e]\nseeds: 1\n"), "");
  // The fuzzer's second finding: valid UTF-8 that the YAML reader decodes into a string that is
  // not (a NUL byte before 'N' in a flow sequence becomes 0x85).
  const std::string decoded_badly(
      "scenario: c\nestimators: [1]\nseeds: 1\nsweep:\n  parameter: _\n"
      "  values: [: \0N]",
      75);
  e = ParseError(decoded_badly);
  EXPECT_NE(e.find("exp.yaml:6: a value the YAML reader decoded is not valid UTF-8"),
            std::string::npos)
      << e;
}

TEST(ExperimentFile, RejectsBadValues) {
  const std::string base = "scenario: s\nestimators: [e]\n";
  const auto expect_error = [](const std::string& text, const std::string& part) {
    const std::string e = ParseError(text);
    EXPECT_NE(e.find(part), std::string::npos) << "text: " << text << "\nerror: " << e;
    EXPECT_EQ(e.rfind("exp.yaml", 0), 0u) << e;
  };
  expect_error("scenario: s\nseeds: 1\n", "'estimators' is required");
  expect_error(base, "'seeds' is required");
  expect_error(base + "seeds: 5-2\n", "reversed");
  expect_error(base + "seeds: 1\nparticles: [1, 0]\n", "< 1");
  expect_error(base + "seeds: 1\nparticles: [10, 10]\n", "listed twice");
  expect_error(base + "seeds: 1\nparticles: [1.5]\n", "not an integer");
  expect_error(base + "seeds: 1\nsteps: -3\n", "'steps'");
  expect_error(base + "seeds: 1\nsteps: many\n", "not an integer");
  expect_error(base + "seeds: 1\nscenario_options: {pd: high}\n", "'pd': expected a number");
  expect_error(base + "seeds: 1\njobs: -1\n", "'jobs'");
  expect_error(base + "seeds: 1\nscenario_options: {clutter_rate: [1]}\n", "expected a number");
  expect_error(base + "seeds: 1\nsweep: {parameter: pd, values: [[1, 2]]}\n", "expected numbers");
  expect_error(base + "seeds: 1\nsweep: {parameter: pd, values: 0.5}\n", "non-empty list");
  expect_error(base + "seeds: 1\nsweep: []\n", "'sweep'");
  expect_error(base +
                   "seeds: 1\nsweep: [{parameter: pd, values: [1]}, {parameter: pd, values: "
                   "[0.5]}]\n",
               "listed twice");
  expect_error(base +
                   "seeds: 1\nscenario_options: {landmarks: 5}\nsweep: {parameter: landmarks, "
                   "values: [4]}\n",
               "is swept");
  expect_error(base + "seeds: 1\nsweep: {parameter: pd, values: []}\n", "non-empty list");
  expect_error(base + "seeds: 1\nsweep: {parameter: pd, values: [0.5, 0.5]}\n", "listed twice");
  expect_error(base + "seeds: 1\nsweep: {parameter: pd}\n", "needs 'parameter'");
  expect_error(base +
                   "seeds: 1\nscenario_options: {pd: 0.5}\nsweep: {parameter: pd, values: "
                   "[0.4]}\n",
               "is swept");
  expect_error("scenario: s\nseeds: 1\nestimators: [e, e]\n", "listed twice");
  expect_error("scenario: s\nseeds: 1\nestimators: []\n", "'estimators'");
  expect_error("scenario: s\nseeds: 1\nestimators: [{set: {a: 1}}]\n", "no 'name'");
  expect_error("scenario: s\nseeds: 1\nestimators: [{name: e, set: 3}]\n", "expected a mapping");
  expect_error("scenario: [a, b]\nseeds: 1\nestimators: [e]\n", "'scenario'");
  expect_error("- a\n- b\n", "expected a mapping");
  expect_error("scenario: s\n  bad indent: [\n", "YAML syntax error");
}

TEST(ExperimentFile, ReadsTheMapOspaSettings) {
  const std::string base = "scenario: s\nestimators: [e]\nseeds: 1\n";
  const Experiment none = ParseExperimentYaml(base, "exp.yaml", "exp");
  EXPECT_FALSE(none.map_ospa.has_value());
  EXPECT_FALSE(none.map_ospa_cutoff.has_value());
  const Experiment x =
      ParseExperimentYaml(base + "map_ospa: true\nmap_ospa_cutoff: 0.5\n", "exp.yaml", "exp");
  EXPECT_EQ(x.map_ospa, true);
  EXPECT_EQ(x.map_ospa_cutoff, 0.5);
  EXPECT_NE(ParseError(base + "map_ospa: yes please\n").find("'map_ospa': expected true or false"),
            std::string::npos);
  EXPECT_NE(ParseError(base + "map_ospa_cutoff: 0\n").find("'map_ospa_cutoff'"), std::string::npos);
  EXPECT_NE(ParseError(base + "map_ospa_cutoff: far\n").find("not a number"), std::string::npos);
}

TEST(ExperimentFile, ReadsAFileWithItsStemAsDefaultName) {
  const std::filesystem::path dir = datasets::testing::FreshTestDir();
  WriteFileAtomically(dir / "my_experiment.yaml",
                      "# a comment\nscenario: generated\nestimators: [odometry]\nseeds: 1-2\n");
  const Experiment x = ReadExperimentFile(dir / "my_experiment.yaml");
  EXPECT_EQ(x.name, "my_experiment");
  EXPECT_EQ(x.source.at("path"), (dir / "my_experiment.yaml").string());
  EXPECT_THROW(ReadExperimentFile(dir / "missing.yaml"), std::runtime_error);
}

}  // namespace
}  // namespace phdslam::validation
