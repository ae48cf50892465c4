#include "validation/runner/experiment/experiment.h"

#include <cmath>
#include <stdexcept>

#include "src/core/parameter_table.h"

namespace phdslam::validation {

void SetScenarioOption(Experiment& experiment, const std::string& key,
                       const nlohmann::json& value) {
  if (key.empty()) throw std::invalid_argument("a scenario option key is empty");
  const bool pd = key == kSweepParameterPd;
  if (pd || key == kSweepParameterClutterRate) {
    if (!value.is_number() || !std::isfinite(value.get<double>())) {
      throw std::invalid_argument("scenario option '" + key + "': expected a number, got " +
                                  params::Shown(value));
    }
    (pd ? experiment.pd : experiment.clutter_rate) = value.get<double>();
    return;
  }
  experiment.scenario_settings[key] = value;
}

}  // namespace phdslam::validation
