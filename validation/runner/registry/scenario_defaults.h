// Estimator parameter defaults that depend on the scenario, as one table: for a (scenario,
// estimator) pair, the parameter overrides applied on top of the estimator's own defaults and
// below the user's (`--set`, experiment files). The filters themselves know no scenario names.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace phdslam::validation {

struct ScenarioDefaultsRow {
  std::string scenario;
  std::vector<std::string> estimators;  ///< the estimators the row applies to
  nlohmann::json parameters;            ///< overrides, keyed as `--set` keys them
  std::string reason;                   ///< where the values come from
};

/// Every row, in the order they are applied.
const std::vector<ScenarioDefaultsRow>& ScenarioDefaultsTable();

/// The merged overrides of every row for `scenario` and `estimator` (an empty object if none).
nlohmann::json ScenarioParameterDefaults(const std::string& scenario, const std::string& estimator);

}  // namespace phdslam::validation
