// What `phdslam list` says about an estimator's parameters: each row of the table that parses its
// `--set` (EstimatorEntry::parameters) with the default the entry resolves to, the accepted values
// the row's one line of meaning and the mode it is used in, if only one.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "validation/runner/registry/estimator_registry.h"

namespace phdslam::validation {

/// One parameter of an estimator as `phdslam list` shows it.
struct EstimatorParameter {
  std::string key;
  nlohmann::json default_value;  ///< null when the resolved parameters have no such key
  std::string accepted;
  std::string meaning;
  std::string
      used_only_with;  ///< the mode it has an effect in (e.g. "resampling=true"); empty: any
};

/// The parameters of `entry` in table order, each with its default: the entry's resolved
/// parameters for one particle, no scenario and no overrides. A run's scenario defaults
/// (scenario_defaults.h) and --particles may differ. Throws what resolved_parameters throws.
std::vector<EstimatorParameter> EstimatorParameters(const EstimatorEntry& entry);

/// One line per parameter, each starting with `indent`: "key = default (accepted): meaning",
/// followed by " [used only with MODE]" for a parameter that has no effect in other modes;
/// one line "(no parameters)" for an estimator without any.
std::string FormatEstimatorParameters(const EstimatorEntry& entry, const std::string& indent);

}  // namespace phdslam::validation
