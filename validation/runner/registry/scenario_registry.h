// The table of scenarios the runner and the command line know. Adding a scenario is one
// ScenarioSpec (scenario_spec.h) in ScenarioTable() (scenario_registry.cc).
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "validation/runner/registry/scenario_entry.h"

namespace phdslam::validation {

/// Every scenario, in the order `phdslam list` shows them.
const std::vector<ScenarioEntry>& ScenarioTable();

/// The entry called `name`; throws std::invalid_argument listing the known names.
const ScenarioEntry& FindScenario(const std::string& name);

/// Checks scenario option `key` = `value` of scenario `name` on its own (as given by
/// `--scenario-set` or a sweep value): its type and range; `pd` and `clutter_rate` are checked as
/// the options they set. Throws std::invalid_argument naming the key for a bad value or unknown
/// key, and for an unknown scenario name.
void CheckScenarioOption(const std::string& name, const std::string& key,
                         const nlohmann::json& value);

/// Monte Carlo run `seed` of scenario `name`, checked with datasets::CheckScenario. Data files
/// are taken from (and loaded into) `cache`.
datasets::Scenario MakeScenario(const std::string& name, std::uint64_t seed,
                                const ScenarioOptions& options, ScenarioCache& cache);

/// Same with a cache of its own (loads the data files on every call).
datasets::Scenario MakeScenario(const std::string& name, std::uint64_t seed,
                                const ScenarioOptions& options);

/// Where the Monte Carlo runner takes its scenarios from.
struct ScenarioSource {
  std::string name;
  /// Every resolved scenario setting, stored in config.json and metrics.json. A "data_dir" key,
  /// if present, is not compared when resuming (the same data may move); a "data_files" key
  /// (relative path -> "sha256:<hex>" of each data file read) is, so other data is refused.
  nlohmann::json options = nlohmann::json::object();
  /// Monte Carlo run `seed`; called concurrently from the worker threads.
  std::function<datasets::Scenario(std::uint64_t seed)> make;
};

/// A source for the registered scenario `name`: resolves (and so validates) the options now and
/// makes scenarios through a cache shared by all calls. Throws std::invalid_argument for an
/// unknown name or a bad option, std::runtime_error for a missing data folder.
ScenarioSource MakeScenarioSource(const std::string& name, const ScenarioOptions& options);

}  // namespace phdslam::validation
