// The parameter table of PhdSlamParams: the resolved configuration stored with results and the
// parameter overrides from experiment files and the command line (`--set name=value`).
#pragma once

#include <nlohmann/json.hpp>

#include "src/core/parameter_table.h"
#include "src/filters/phd_slam_params.h"

namespace phdslam::filters {

const params::ParameterTable<PhdSlamParams>& PhdSlamParamsTable();

/// Every parameter by name (flat object; matrices as arrays of their diagonal).
nlohmann::json ToJson(const PhdSlamParams& params);

/// Applies the keys of `overrides` to `params`. Throws std::invalid_argument naming the key when a
/// key is unknown or a value has the wrong type or is out of range.
void ApplyJson(const nlohmann::json& overrides, PhdSlamParams& params);

}  // namespace phdslam::filters
