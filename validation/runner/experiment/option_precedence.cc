#include "validation/runner/experiment/option_precedence.h"

#include <stdexcept>
#include <utility>

#include "datasets/simulation_limits.h"
#include "validation/runner/io/list_arguments.h"
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

namespace {

// --estimator: the named estimators, each with the file's settings when the file lists it.
std::vector<ExperimentEstimator> SelectEstimators(const std::string& names,
                                                  const std::vector<ExperimentEstimator>& in_file) {
  std::vector<ExperimentEstimator> selected;
  for (const std::string& name : ParseNameList(names, "estimator")) {
    ExperimentEstimator e{name};
    for (const ExperimentEstimator& listed : in_file) {
      if (listed.name == name) e = listed;  // keeps the file's `set` and `particles`
    }
    selected.push_back(std::move(e));
  }
  return selected;
}

void RequireWithoutFile(const ExperimentOptions& o) {
  const std::pair<bool, const char*> required[] = {{o.scenario.has_value(), "--scenario"},
                                                   {o.estimators.has_value(), "--estimator"},
                                                   {o.seeds.has_value(), "--seeds"}};
  for (const auto& [given, name] : required) {
    if (!given) {
      throw std::invalid_argument(std::string("run: ") + name +
                                  " is required (or give --experiment)");
    }
  }
}

}  // namespace

Experiment ResolveExperiment(const ExperimentOptions& o) {
  Experiment x;
  if (o.file) {
    x = ReadExperimentFile(*o.file);
  } else {
    RequireWithoutFile(o);
  }
  std::vector<std::string> overridden;
  const auto given = [&](bool is_given, const char* name) {
    if (is_given) overridden.emplace_back(name);
    return is_given;
  };
  if (given(o.scenario.has_value(), "--scenario")) x.scenario = *o.scenario;
  if (given(o.estimators.has_value(), "--estimator")) {
    x.estimators = SelectEstimators(*o.estimators, x.estimators);
  }
  if (given(o.particles.has_value(), "--particles")) x.particles = ParseParticleList(*o.particles);
  if (given(o.seeds.has_value(), "--seeds")) x.seeds = ParseSeedList(*o.seeds);
  if (given(o.steps.has_value(), "--steps")) x.steps = *o.steps;
  if (given(o.jobs.has_value(), "--jobs")) x.jobs = *o.jobs;
  if (given(o.name.has_value(), "--experiment-name")) x.name = *o.name;
  if (given(o.pd.has_value(), "--pd")) x.pd = CheckedScenarioNumber(x, "--pd", "pd", *o.pd);
  if (given(o.clutter_rate.has_value(), "--clutter-rate")) {
    x.clutter_rate = CheckedScenarioNumber(x, "--clutter-rate", "clutter_rate", *o.clutter_rate);
  }
  if (o.data_dir) x.data_dir = *o.data_dir;
  given(!o.assignments.empty(), "--set");
  ApplyParameterAssignments(o.assignments, x);
  given(!o.scenario_assignments.empty(), "--scenario-set");
  ApplyScenarioAssignments(o.scenario_assignments, x);
  if (o.file) x.source["command_line"] = overridden;
  return x;
}

}  // namespace phdslam::validation
