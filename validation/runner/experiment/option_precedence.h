// Which value wins when `phdslam run` gets an experiment file and command-line options: every
// option given on the command line takes precedence over the file's value, and the options that
// did are recorded in the experiment's source (config.json "experiment_file"."command_line").
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "validation/runner/experiment/experiment_file.h"

namespace phdslam::validation {

/// The experiment options of `phdslam run`: the file and the options of the experiment key table
/// (experiment_keys.h) that were given on the command line.
struct ExperimentOptions {
  std::optional<std::string> file;  ///< --experiment
  /// Option as typed ("--steps") -> its value, as JSON of the option's OptionKind; only the
  /// options given.
  std::map<std::string, nlohmann::json> given;
};

/// The experiment of `options`: the experiment file, if any, with every option given taking
/// precedence over the file's value. --estimator selects estimators by name, keeping the file's
/// `set` and `particles` of those it lists; --set and --scenario-set apply after the file's
/// values. Without a file, --scenario, --estimator and --seeds are required (std::invalid_argument
/// "run: --scenario is required (or give --experiment)"). With a file, Experiment::source gets
/// "command_line": the options that overrode it, in the order of the key table.
Experiment ResolveExperiment(const ExperimentOptions& options);

/// Applies the options of `given` (as ExperimentOptions::given) to `x` in the order of the key
/// table, each with its row's apply_option; returns those applied that are not machine settings.
/// Throws std::invalid_argument for an option no key has, or a value its row refuses.
std::vector<std::string> ApplyGivenOptions(const std::map<std::string, nlohmann::json>& given,
                                           Experiment& x);

}  // namespace phdslam::validation
