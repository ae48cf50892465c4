#include "validation/runner/experiment/experiment_assignments.h"

#include <stdexcept>

#include "datasets/simulation_limits.h"
#include "validation/runner/registry/parameter_overrides.h"
#include "validation/runner/registry/scenario_registry.h"

namespace phdslam::validation {

void ApplyParameterAssignments(const std::vector<std::string>& assignments, Experiment& x) {
  for (const std::string& text : assignments) {
    const ParameterAssignment assignment = ParseParameterAssignment(text);
    bool matched = assignment.estimator.empty();
    for (ExperimentEstimator& e : x.estimators) {
      if (assignment.estimator.empty() || assignment.estimator == e.name) {
        MergeJsonObjects(e.overrides, assignment.overrides);
        matched = true;
      }
    }
    if (!matched) {
      throw std::invalid_argument("--set '" + text + "': estimator '" + assignment.estimator +
                                  "' is not among the experiment's estimators");
    }
  }
}

void ApplyScenarioAssignments(const std::vector<std::string>& assignments, Experiment& x) {
  for (const std::string& text : assignments) {
    const ParameterAssignment assignment = ParseParameterAssignment(text, "--scenario-set");
    if (!assignment.estimator.empty() || assignment.overrides.size() != 1 ||
        assignment.overrides.begin()->is_object()) {
      throw std::invalid_argument("--scenario-set '" + text + "': expected key=value");
    }
    try {
      const std::string& key = assignment.overrides.begin().key();
      const nlohmann::json& value = *assignment.overrides.begin();
      if (!x.scenario.empty()) CheckScenarioOption(x.scenario, key, value);
      SetScenarioOption(x, key, value);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--scenario-set '" + text + "': " + e.what());
    }
  }
}

double CheckedScenarioNumber(const Experiment& x, const std::string& option, const std::string& key,
                             double value) {
  try {
    if (!x.scenario.empty()) CheckScenarioOption(x.scenario, key, value);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(option + " " + datasets::CompactNumber(value) + ": " + e.what());
  }
  return value;
}

}  // namespace phdslam::validation
