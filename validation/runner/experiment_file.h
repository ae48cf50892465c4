// Experiment files: one YAML file per Monte Carlo experiment (validation/experiments/*.yaml),
// read into an Experiment. The keys are documented in validation/README.md; every setting not in
// the file keeps the paper's default (the estimator table and the scenario supply them).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace phdslam::validation {

struct ExperimentEstimator {
  std::string name;
  nlohmann::json overrides = nlohmann::json::object();  ///< `set:` of the file, `--set`
  std::vector<int> particles = {};                      ///< empty: the experiment's list
};

/// Scenario parameters a sweep may vary.
inline constexpr const char* kSweepParameterPd = "pd";
inline constexpr const char* kSweepParameterClutterRate = "clutter_rate";

struct ExperimentSweep {
  std::string parameter;  ///< kSweepParameterPd or kSweepParameterClutterRate
  std::vector<double> values;
};

/// Everything that selects the runs of an experiment.
struct Experiment {
  std::string name = "default";  ///< part of every estimator's stream seed
  std::string scenario;
  std::vector<ExperimentEstimator> estimators;
  std::vector<int> particles = {1};
  std::vector<std::uint64_t> seeds;
  int steps = 0;                        ///< 0 = the scenario's full length
  std::optional<double> pd;             ///< detection probability override
  std::optional<double> clutter_rate;   ///< clutter rate override
  std::optional<std::string> data_dir;  ///< a machine setting: never read from files
  std::optional<int> jobs;              ///< worker threads (0 or unset: one per hardware thread)
  std::optional<ExperimentSweep> sweep;
  /// Where the experiment came from, stored in config.json as "experiment_file": {"path",
  /// "text", "values" (the file as JSON), "command_line" (options that overrode it)}; null when
  /// the experiment was given on the command line only.
  nlohmann::json source = nullptr;
};

/// Parses an experiment file's text. `source` names the file in error messages and in
/// Experiment::source; `default_name` is the experiment name when the file has no `name`.
/// Throws std::invalid_argument "<source>:<line>: ..." for YAML syntax errors, unknown keys,
/// missing required keys (scenario, estimators, seeds) and values of the wrong kind.
Experiment ParseExperimentYaml(std::string_view text, const std::string& source,
                               const std::string& default_name);

/// Reads and parses an experiment file; the default name is the file's stem. Throws
/// std::runtime_error when the file cannot be read.
Experiment ReadExperimentFile(const std::filesystem::path& path);

}  // namespace phdslam::validation
