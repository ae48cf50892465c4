// Which value wins when `phdslam run` gets an experiment file and command-line options: every
// option given on the command line takes precedence over the file's value, and the options that
// did are recorded in the experiment's source (config.json "experiment_file"."command_line").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "validation/runner/experiment/experiment_file.h"

namespace phdslam::validation {

/// The experiment options of `phdslam run`, each set only when it was given on the command line.
struct ExperimentOptions {
  std::optional<std::string> file;        ///< --experiment
  std::optional<std::string> scenario;    ///< --scenario
  std::optional<std::string> estimators;  ///< --estimator, a comma list of names
  std::optional<std::string> particles;   ///< --particles, a list
  std::optional<std::string> seeds;       ///< --seeds, a list
  std::optional<int> steps;               ///< --steps
  std::optional<int> jobs;                ///< --jobs
  std::optional<std::string> name;        ///< --experiment-name
  std::optional<double> pd;               ///< --pd
  std::optional<double> clutter_rate;     ///< --clutter-rate
  std::optional<std::string> data_dir;    ///< --data-dir (a machine setting, never recorded)
  std::vector<std::string> assignments;   ///< --set [estimator:]key=value
  std::vector<std::string> scenario_assignments;  ///< --scenario-set key=value
};

/// The experiment of `options`: the experiment file, if any, with every option given taking
/// precedence over the file's value. --estimator selects estimators by name, keeping the file's
/// `set` and `particles` of those it lists; --set and --scenario-set apply after the file's
/// values. Without a file, --scenario, --estimator and --seeds are required (std::invalid_argument
/// "run: --scenario is required (or give --experiment)"). With a file, Experiment::source gets
/// "command_line": the options that overrode it, in the order of the fields above.
Experiment ResolveExperiment(const ExperimentOptions& options);

/// Applies --set assignments ([estimator:]key=value) to the experiment's estimators. Throws
/// std::invalid_argument naming the assignment when its estimator is not in the experiment.
void ApplyParameterAssignments(const std::vector<std::string>& assignments, Experiment& x);

/// Applies --scenario-set assignments (key=value) to the experiment's scenario options. Throws
/// std::invalid_argument naming the assignment for an estimator prefix, a nested key or a value
/// SetScenarioOption refuses.
void ApplyScenarioAssignments(const std::vector<std::string>& assignments, Experiment& x);

/// `value` of command-line option `option` (scenario option `key`, e.g. "--pd" and "pd"),
/// checked against the option table of x.scenario when it is set; std::invalid_argument naming
/// the option as typed otherwise.
double CheckedScenarioNumber(const Experiment& x, const std::string& option, const std::string& key,
                             double value);

}  // namespace phdslam::validation
