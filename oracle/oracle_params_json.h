// The parameter table of OracleParams: the resolved configuration stored with results and the
// parameter overrides from experiment files and the command line (`--set oracle:key=value`).
#pragma once

#include <nlohmann/json.hpp>

#include "oracle/oracle_rbpf.h"
#include "src/core/parameter_table.h"

namespace phdslam::oracle {

/// particles, resampling, ess_threshold (x N), ipl_iterations, ipl_kl_tolerance,
/// pose_regularisation (the diagonal [qx, qy, qtheta]).
const params::ParameterTable<OracleParams>& OracleParamsTable();

/// Every parameter by name.
nlohmann::json ToJson(const OracleParams& params);

/// Applies the keys of `overrides` (an object) to `params`, then validates the result. Throws
/// std::invalid_argument naming the key when a key is unknown, a value has the wrong type, or
/// the result fails OracleParams::Validate(); `params` is unchanged after a throw.
void ApplyJson(const nlohmann::json& overrides, OracleParams& params);

}  // namespace phdslam::oracle
