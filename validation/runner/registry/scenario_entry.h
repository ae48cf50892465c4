// What the registry knows of one scenario (ScenarioEntry) and what a run may ask of it
// (ScenarioOptions); the entries are made from tables (scenario_spec.h, scenario_registry.cc).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "validation/runner/registry/scenario_cache.h"

namespace phdslam::validation {

/// Scenario settings a run may change; unset values keep the scenario's defaults.
struct ScenarioOptions {
  /// --data-dir; when unset, PHDSLAM_DATA and then the compiled default (datasets::ResolveDataDir).
  /// paper-synthetic reads the repository's copy (datasets::ResolveDataDirFor) when this folder
  /// does not hold its file; victoria-park and mrclam need the folder.
  std::optional<std::string> data_dir;
  int steps = 0;  ///< limit on the number of filter steps; 0 = the scenario's full length
  /// The shorthand options pd and clutter_rate (scenario_shorthands.h), each applied to the rows
  /// of the scenario's option table it names (ScenarioEntry::shorthand_rows). Detection
  /// probability: the constant pD (synthetic scenarios) or the pD at zero range (Victoria Park,
  /// where it also sets the nominal pD of the estimate threshold).
  std::optional<double> detection_probability;
  std::optional<double> clutter_rate;  ///< Poisson mean of clutter points per scan
  /// Further options by key (`scenario_options`, `--scenario-set`), applied after the two above
  /// through the scenario's option table (scenario_option_tables.h).
  nlohmann::json settings = nlohmann::json::object();
};

/// One key a scenario accepts in ScenarioOptions::settings, with the values it accepts.
struct ScenarioOptionHelp {
  std::string key;
  std::string help;
};

struct ScenarioEntry {
  std::string name;
  std::string description;
  bool uses_data_dir = true;
  /// The keys of ScenarioOptions::settings, in table order.
  std::vector<ScenarioOptionHelp> option_keys;
  /// Checks one option's value against its row (type, finiteness, range); throws
  /// std::invalid_argument naming the key. Unset: no per-key check.
  std::function<void(const std::string& key, const nlohmann::json& value)> check_option;
  /// Monte Carlo run `seed` of the scenario; deterministic in (seed, options, data).
  std::function<datasets::Scenario(std::uint64_t seed, const ScenarioOptions&, ScenarioCache&)>
      make;
  /// Every scenario setting after defaults and options (for config.json); throws
  /// std::invalid_argument naming the key for an unknown key or an out-of-range option and
  /// std::runtime_error for a missing data folder, so a bad request fails before any run starts.
  std::function<nlohmann::json(const ScenarioOptions&)> resolved_options;
  /// Per shorthand option (scenario_shorthands.h: pd, clutter_rate), the keys of option_keys it
  /// sets.
  std::map<std::string, std::vector<std::string>> shorthand_rows;
  /// The cut-off c (m) of the final-map GOSPA for this scenario's scale of map, when it differs
  /// from MetricSettings' default (the runner applies it; config.json records it).
  std::optional<double> gospa_c;
};

}  // namespace phdslam::validation
