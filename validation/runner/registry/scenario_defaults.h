// Estimator parameter defaults that depend on the scenario, as one table: for a (scenario,
// estimator) pair, the parameter overrides applied on top of the estimator's own defaults and
// below the user's (`--set`, experiment files). The filters themselves know no scenario names.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
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

/// The labelled filters' survival probability p_S for a scenario whose detection probability is
/// `detection_probability` (in (0, 1]; else std::invalid_argument): the delta-GLMB paper's ratio
/// of death to missed detection, (1 - p_S) / (1 - pD) = 0.05 / 0.3 (its p_S 0.95 at its pD 0.7),
/// kept at every pD: p_S = min(0.95 + (pD - 0.7) / 6, 0.998), so pD 0.95 gives 0.991666...,
/// pD 0.7 exactly 0.95, and pD above 0.988 (pD 1 included) 0.998, which keeps a hypothesis in
/// which an unmeasured landmark in view died. docs/algorithms/glmb-slam.md section 2.2.
double SurvivalProbabilityForDetection(double detection_probability);

/// The scenario's nominal detection probability from its resolved options (ScenarioSource::
/// options): `detection_probability_nominal` when the scenario has one (a range-dependent pD,
/// such as Victoria Park's), else `detection_probability`; nullopt when it has neither.
std::optional<double> NominalDetectionProbability(const nlohmann::json& resolved_options);

/// The merged overrides for `scenario` and `estimator` (an empty object if none): first the
/// defaults derived from the scenario's nominal detection probability when it is known (the
/// labelled filters' survival_probability, SurvivalProbabilityForDetection), then every row of
/// ScenarioDefaultsTable() in order, so a row for the scenario overrides a derived value.
nlohmann::json ScenarioParameterDefaults(const std::string& scenario, const std::string& estimator,
                                         std::optional<double> detection_probability = {});

}  // namespace phdslam::validation
