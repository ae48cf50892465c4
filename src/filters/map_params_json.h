// The GM-PHD map parameters (phd::MapParams) as JSON keys, shared by every filter that carries
// GM-PHD maps so that each parameter has one name and one range check.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "src/phd/map_params.h"

namespace phdslam::filters {

/// Writes every map parameter into `j` under its name.
void WriteMapParams(const phd::MapParams& params, nlohmann::json& j);

/// Applies one override when `key` names a map parameter and returns true; returns false for any
/// other key. Throws std::invalid_argument naming the key for a wrong type or range.
bool ApplyMapParam(const std::string& key, const nlohmann::json& value, phd::MapParams& params);

}  // namespace phdslam::filters
