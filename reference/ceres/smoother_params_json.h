// The parameter table of SmootherOptions: the resolved configuration stored with results and the
// parameter overrides from experiment files and the command line (`--set
// smoother-known:key=value`).
#pragma once

#include <nlohmann/json.hpp>

#include "reference/ceres/batch_smoother.h"
#include "src/core/parameter_table.h"

namespace phdslam::reference {

/// Every option by name except the data fields (filter_association, initial_poses):
/// association ("known" | "filter" | "unknown"), initialisation, incremental_chunk_steps,
/// incremental_active_steps, incremental_held_prior, incremental_squared_marginals,
/// incremental_delete_collapsed, incremental_marginals_without_collapsed,
/// incremental_skip_ambiguous, incremental_birth_outside_gates, known_outlier_chi2, max_iterations,
/// function_tolerance, intermediate_function_tolerance, compute_covariances, linear_solver
/// ("sparse_normal_cholesky" | "sparse_schur"), num_threads, odometry_residual
/// ("control_space" | "pose_space"), odometry_floor and warm_start_floor
/// ([position_std, heading_std]), initial_pass_solve_steps, reassociation_rounds, gate_chi2,
/// min_observations, merge_position_std, min_detection_ratio, robust_loss, robust_scale,
/// filter_label_distance. The association mode is fixed by the estimator's name: an input equal
/// to the current mode is accepted (a no-op), any other is rejected naming the key.
const params::ParameterTable<SmootherOptions>& SmootherOptionsTable();

/// Every option by name.
nlohmann::json ToJson(const SmootherOptions& options);

/// Applies the keys of `overrides` (an object) to `options`, then validates the result. Throws
/// std::invalid_argument naming the key when a key is unknown, a value has the wrong type or is
/// out of range, `association` differs from options.association, or the result fails
/// SmootherOptions::Validate(); `options` is unchanged after a throw.
void ApplyJson(const nlohmann::json& overrides, SmootherOptions& options);

}  // namespace phdslam::reference
