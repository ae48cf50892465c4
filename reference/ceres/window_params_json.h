// The parameter table of WindowParams (fixed_lag_smoother.h): the resolved configuration stored
// with results and the overrides from experiment files and the command line
// (`--set window:window_length=40`).
#pragma once

#include <nlohmann/json.hpp>

#include "reference/ceres/fixed_lag_smoother.h"
#include "src/core/parameter_table.h"

namespace phdslam::reference {

/// association ("known" | "unknown", fixed by the estimator's name: window-known, window),
/// window_length, solve_every, max_iterations, function_tolerance, odometry_residual
/// ("control_space" | "pose_space"), odometry_floor ([position_std, heading_std]), gate_chi2,
/// confirm_detections, confirm_ratio, robust_loss, robust_scale, tentative_robust_scale,
/// reject_outliers.
const params::ParameterTable<WindowParams>& WindowParamsTable();

nlohmann::json ToJson(const WindowParams& params);

/// Applies `overrides` to `params`, then validates (without a run length); throws
/// std::invalid_argument naming the key; `params` is unchanged after a throw.
void ApplyJson(const nlohmann::json& overrides, WindowParams& params);

}  // namespace phdslam::reference
