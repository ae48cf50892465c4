// The assignments of the command line to an Experiment: `--set` ([estimator:]key=value) to its
// estimators' overrides, `--scenario-set` (key=value) and the numbers of `--pd` and
// `--clutter-rate` to its scenario options, each checked against the registry's tables. The
// experiment key table (experiment_keys.cc) applies its options with these.
#pragma once

#include <string>
#include <vector>

#include "validation/runner/experiment/experiment.h"

namespace phdslam::validation {

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
