// SmootherOptions <-> JSON, for the resolved configuration stored with results and for parameter
// overrides from experiment files and the command line (`--set smoother-known:key=value`).
#pragma once

#include <nlohmann/json.hpp>

#include "reference/ceres/batch_smoother.h"

namespace phdslam::reference {

/// Every option by name except filter_association (data, not a parameter):
/// association ("known" | "filter" | "unknown"), max_iterations, function_tolerance,
/// intermediate_function_tolerance, compute_covariances, linear_solver
/// ("sparse_normal_cholesky" | "sparse_schur"), num_threads, odometry_residual
/// ("control_space" | "pose_space"), odometry_floor and warm_start_floor
/// ([position_std, heading_std]), initial_pass_solve_steps, reassociation_rounds, gate_chi2,
/// min_observations, merge_position_std, min_detection_ratio, robust_loss, robust_scale,
/// filter_label_distance.
nlohmann::json ToJson(const SmootherOptions& options);

/// Applies the keys of `overrides` (an object) to `options`, then validates the result. The
/// association mode is fixed by the estimator's name and cannot be overridden. Throws
/// std::invalid_argument naming the key when a key is unknown, a value has the wrong type, or the
/// result fails SmootherOptions::Validate(); `options` is unchanged after a throw.
void ApplyJson(const nlohmann::json& overrides, SmootherOptions& options);

}  // namespace phdslam::reference
