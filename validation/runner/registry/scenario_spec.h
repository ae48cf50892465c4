// One scenario of the registry as data: its name and description, its options struct with the
// option table, how the step limit, the shorthand options (pd, clutter_rate) and the data folder
// reach it, and how a run is made from the resolved options. EntryFromSpec turns one such table
// into the registry's ScenarioEntry, so that the scenarios differ only in their tables
// (ScenarioTable(), scenario_registry.cc).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/parameter_table.h"
#include "validation/runner/registry/scenario_entry.h"
#include "validation/runner/registry/scenario_shorthands.h"

namespace phdslam::validation {

/// How the run's step limit (ScenarioOptions::steps, 0 = the full length) reaches the options.
enum class StepLimit {
  kZeroIsAll,         ///< the member takes the limit as given; the scenario reads 0 as all
  kZeroKeepsDefault,  ///< the member takes a limit > 0; its default is the scenario's length
};

template <class Options>
struct ScenarioSpec {
  std::string name{};
  std::string description{};
  const params::ParameterTable<Options>* options_table = nullptr;
  int Options::*steps = nullptr;  ///< the member the step limit sets
  StepLimit step_limit = StepLimit::kZeroKeepsDefault;
  /// Per shorthand option, the rows of options_table it sets.
  std::map<std::string, std::vector<std::string>> shorthand_rows = DefaultShorthandRows();
  /// The data folder a run reads; unset: the scenario reads no data files.
  std::function<std::filesystem::path(const ScenarioOptions&)> data_dir{};
  /// The files read from that folder, relative to it (recorded with their checksums).
  std::function<std::vector<std::filesystem::path>(const std::filesystem::path&, const Options&)>
      data_files{};
  /// Monte Carlo run `seed` from the resolved options (`data_dir` empty without data files).
  std::function<datasets::Scenario(const Options&, std::uint64_t seed,
                                   const std::filesystem::path& data_dir, ScenarioCache&)>
      make{};
  /// Further resolved settings for config.json, after the table's; may be unset.
  std::function<void(const Options&, const std::filesystem::path& data_dir, nlohmann::json&)>
      describe_data{};
  std::optional<double> gospa_c{};  ///< ScenarioEntry::gospa_c
};

/// Throws std::invalid_argument unless 0 <= steps <= datasets::kMaxSimulatedSteps.
void RequireStepLimitInRange(int steps);

/// {"<relative path>": "sha256:<hex>"} of each of `files` present in `data_dir`.
nlohmann::json DataFileChecksums(const std::filesystem::path& data_dir,
                                 const std::vector<std::filesystem::path>& files);

/// The options of one run: the struct's defaults, the step limit, the shorthand options through
/// their rows, then ScenarioOptions::settings, each checked by the table (errors name the
/// scenario and the key), then the struct's own Validate().
template <class Options>
Options ResolveScenarioOptions(const ScenarioSpec<Options>& spec, const ScenarioOptions& options) {
  RequireStepLimitInRange(options.steps);
  Options o;
  if (spec.step_limit == StepLimit::kZeroIsAll || options.steps > 0) o.*spec.steps = options.steps;
  try {
    spec.options_table->Apply(ShorthandSettings(spec.shorthand_rows, options), o);
    spec.options_table->Apply(options.settings, o);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("scenario '" + spec.name + "' option: " + e.what());
  }
  o.Validate();
  return o;
}

/// Every resolved setting of a run (config.json): the table's values, the data folder with the
/// checksums of its files, the step limit and describe_data's additions.
template <class Options>
nlohmann::json ResolvedScenarioJson(const ScenarioSpec<Options>& spec,
                                    const ScenarioOptions& options) {
  const Options o = ResolveScenarioOptions(spec, options);
  nlohmann::json j = spec.options_table->ToJson(o);
  std::filesystem::path data_dir;
  if (spec.data_dir) {
    data_dir = spec.data_dir(options);
    j["data_dir"] = data_dir.string();
    j["data_files"] = DataFileChecksums(data_dir, spec.data_files(data_dir, o));
  }
  j["steps"] = o.*spec.steps;
  if (spec.describe_data) spec.describe_data(o, data_dir, j);
  return j;
}

/// The registry entry of `spec`.
template <class Options>
ScenarioEntry EntryFromSpec(const ScenarioSpec<Options>& spec) {
  ScenarioEntry e;
  e.name = spec.name;
  e.description = spec.description;
  e.uses_data_dir = static_cast<bool>(spec.data_dir);
  e.gospa_c = spec.gospa_c;
  e.shorthand_rows = spec.shorthand_rows;
  for (const params::Field<Options>& f : spec.options_table->fields()) {
    e.option_keys.push_back({f.key, f.help});
  }
  e.check_option = [table = spec.options_table](const std::string& key,
                                                const nlohmann::json& value) {
    Options o;
    table->Apply(nlohmann::json::object({{key, value}}), o);
  };
  e.make = [spec](std::uint64_t seed, const ScenarioOptions& options, ScenarioCache& cache) {
    const Options o = ResolveScenarioOptions(spec, options);
    const std::filesystem::path data_dir = spec.data_dir ? spec.data_dir(options) : "";
    return spec.make(o, seed, data_dir, cache);
  };
  e.resolved_options = [spec](const ScenarioOptions& options) {
    return ResolvedScenarioJson(spec, options);
  };
  return e;
}

}  // namespace phdslam::validation
