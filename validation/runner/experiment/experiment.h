// An experiment: everything that selects the runs of a Monte Carlo experiment, whether it comes
// from an experiment file (experiment_file.h), the command line (option_precedence.h) or an
// export manifest. Below every reader of it, so the table of its keys (experiment_keys.h) and the
// readers that follow the table need nothing of one another to name it.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace phdslam::validation {

struct ExperimentEstimator {
  std::string name;
  nlohmann::json overrides = nlohmann::json::object();  ///< `set:` of the file, `--set`
  std::vector<int> particles = {};                      ///< empty: the experiment's list
};

/// Scenario options with a key of their own (`--pd`, `--clutter-rate`): `pd` sets the scenario's
/// detection probability (both pD settings of Victoria Park).
inline constexpr const char* kSweepParameterPd = "pd";
inline constexpr const char* kSweepParameterClutterRate = "clutter_rate";
/// Sweep parameters that are not scenario options or estimator parameters.
inline constexpr const char* kSweepParameterParticles = "particles";
inline constexpr const char* kSweepParameterSteps = "steps";

/// One swept parameter: `pd`, `clutter_rate`, any other option of the scenario, `particles`,
/// `steps`, or an estimator parameter named as `--set` names it (`[estimator:]key[.subkey]`).
struct ExperimentSweep {
  std::string parameter;
  std::vector<nlohmann::json> values;  ///< scalars (numbers, true/false, strings), none twice
};

/// Everything that selects the runs of an experiment.
struct Experiment {
  std::string name = "default";  ///< part of every estimator's stream seed
  std::string scenario;
  std::vector<ExperimentEstimator> estimators;
  std::vector<int> particles = {1};
  std::vector<std::uint64_t> seeds;
  int steps = 0;                       ///< 0 = the scenario's full length
  std::optional<double> pd;            ///< detection probability override
  std::optional<double> clutter_rate;  ///< clutter rate override
  /// Other scenario options by key (`scenario_options`, `--scenario-set`), checked against the
  /// scenario's option table when the experiment is planned.
  nlohmann::json scenario_settings = nlohmann::json::object();
  std::optional<std::string> data_dir;  ///< a machine setting: never read from files
  std::optional<int> jobs;              ///< worker threads (0 or unset: one per hardware thread)
  /// `map_ospa: true` records the per-step map OSPA (as `run --map-ospa`); `map_ospa_cutoff`
  /// sets its cut-off c in m (and turns it on). Unset: off, c = 5 m.
  std::optional<bool> map_ospa;
  std::optional<double> map_ospa_cutoff;
  /// Swept parameters: empty without a sweep, one for a one-dimensional sweep, several for a
  /// grid (every combination, the first parameter varying slowest).
  std::vector<ExperimentSweep> sweep;
  /// Where the experiment came from, stored in config.json as "experiment_file": {"path",
  /// "text", "values" (the file as JSON), "command_line" (options that overrode it)}; null when
  /// the experiment was given on the command line only.
  nlohmann::json source = nullptr;
};

/// The member of Experiment that holds shorthand scenario option `key` (the registry's table,
/// scenario_shorthands.h: pd, clutter_rate); nullptr for any other key.
std::optional<double> Experiment::*ShorthandMember(const std::string& key);

/// Sets scenario option `key` (a `scenario_options` key or a `--scenario-set` key): a shorthand
/// (`pd`, `clutter_rate`) sets its ShorthandMember (a number), other keys enter
/// scenario_settings. Throws std::invalid_argument naming the key for a shorthand's non-number.
void SetScenarioOption(Experiment& experiment, const std::string& key, const nlohmann::json& value);

/// True when `experiment` sets scenario option `key` itself: a shorthand's member, or a key of
/// scenario_settings.
bool SetsScenarioOption(const Experiment& experiment, const std::string& key);

}  // namespace phdslam::validation
