#include "validation/runner/experiment/option_precedence.h"

#include <stdexcept>

#include "validation/runner/experiment/experiment_keys.h"

namespace phdslam::validation {

namespace {

void RequireWithoutFile(const ExperimentOptions& o) {
  for (const ExperimentKey& key : ExperimentKeys()) {
    if (key.required && !o.given.contains(key.option)) {
      throw std::invalid_argument("run: " + key.option + " is required (or give --experiment)");
    }
  }
}

}  // namespace

std::vector<std::string> ApplyGivenOptions(const std::map<std::string, nlohmann::json>& given,
                                           Experiment& x) {
  for (const auto& [option, value] : given) {
    if (FindExperimentOption(option) == nullptr) {
      throw std::invalid_argument(option + " is not an option of an experiment");
    }
  }
  std::vector<std::string> applied;
  for (const ExperimentKey& key : ExperimentKeys()) {
    const auto value = key.option.empty() ? given.end() : given.find(key.option);
    if (value == given.end()) continue;
    key.apply_option(value->second, x);
    if (!key.machine_setting) applied.push_back(key.option);
  }
  return applied;
}

Experiment ResolveExperiment(const ExperimentOptions& o) {
  Experiment x;
  if (o.file) {
    x = ReadExperimentFile(*o.file);
  } else {
    RequireWithoutFile(o);
  }
  const std::vector<std::string> overridden = ApplyGivenOptions(o.given, x);
  if (o.file) x.source["command_line"] = overridden;
  return x;
}

}  // namespace phdslam::validation
