// The table of scenarios the runner and the command line know. Adding a scenario is one entry in
// ScenarioTable() (scenario_registry.cc).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "datasets/mrclam.h"
#include "datasets/paper_synthetic.h"
#include "datasets/scenario.h"
#include "datasets/victoria_park.h"

namespace phdslam::validation {

/// Scenario settings a run may change; unset values keep the scenario's defaults.
struct ScenarioOptions {
  /// --data-dir; when unset, PHDSLAM_DATA and then the compiled default (datasets::ResolveDataDir).
  /// paper-synthetic reads the repository's copy (datasets::ResolveDataDirFor) when this folder
  /// does not hold its file; victoria-park and mrclam need the folder.
  std::optional<std::string> data_dir;
  int steps = 0;  ///< limit on the number of filter steps; 0 = the scenario's full length
  /// Detection probability: the constant pD (synthetic scenarios) or the pD at zero range
  /// (Victoria Park, where it also sets the nominal pD of the estimate threshold).
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

/// Data files loaded once and shared by every run of an invocation (keyed by data folder).
/// Thread-safe: concurrent callers wait for one load.
class ScenarioCache {
 public:
  const datasets::PaperSyntheticEnvironment& PaperSynthetic(const std::filesystem::path& data_dir);
  const datasets::VictoriaParkData& VictoriaPark(const std::filesystem::path& data_dir);
  const datasets::MrclamRobotData& Mrclam(const std::filesystem::path& data_dir, int dataset,
                                          int robot);

 private:
  std::mutex mutex_;
  std::map<std::filesystem::path, std::unique_ptr<const datasets::PaperSyntheticEnvironment>>
      paper_synthetic_;
  std::map<std::filesystem::path, std::unique_ptr<const datasets::VictoriaParkData>> victoria_park_;
  std::map<std::tuple<std::filesystem::path, int, int>,
           std::unique_ptr<const datasets::MrclamRobotData>>
      mrclam_;
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
  /// The cut-off c (m) of the final-map GOSPA for this scenario's scale of map, when it differs
  /// from MetricSettings' default (the runner applies it; config.json records it).
  std::optional<double> gospa_c;
};

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
