#include "validation/runner/experiment/experiment.h"

#include <cmath>
#include <map>
#include <stdexcept>

#include "src/core/parameter_table.h"
#include "validation/runner/registry/scenario_shorthands.h"

namespace phdslam::validation {

std::optional<double> Experiment::*ShorthandMember(const std::string& key) {
  static const std::map<std::string, std::optional<double> Experiment::*> members = {
      {kSweepParameterPd, &Experiment::pd},
      {kSweepParameterClutterRate, &Experiment::clutter_rate},
  };
  const auto it = members.find(key);
  return FindScenarioShorthand(key) == nullptr || it == members.end() ? nullptr : it->second;
}

void SetScenarioOption(Experiment& experiment, const std::string& key,
                       const nlohmann::json& value) {
  if (key.empty()) throw std::invalid_argument("a scenario option key is empty");
  if (const auto member = ShorthandMember(key)) {
    if (!value.is_number() || !std::isfinite(value.get<double>())) {
      throw std::invalid_argument("scenario option '" + key + "': expected a number, got " +
                                  params::Shown(value));
    }
    experiment.*member = value.get<double>();
    return;
  }
  experiment.scenario_settings[key] = value;
}

bool SetsScenarioOption(const Experiment& experiment, const std::string& key) {
  const auto member = ShorthandMember(key);
  return member != nullptr ? (experiment.*member).has_value()
                           : experiment.scenario_settings.contains(key);
}

}  // namespace phdslam::validation
