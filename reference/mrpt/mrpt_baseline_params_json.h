// The parameter tables of MrptEkfSlamOptions and FastSlamOptions: the resolved configuration
// stored with results and the parameter overrides (`--set mrpt-ekf:key=value`, experiment files).
#pragma once

#include <nlohmann/json.hpp>

#include "reference/mrpt/fastslam_options.h"
#include "reference/mrpt/mrpt_ekf_slam_options.h"
#include "src/core/parameter_table.h"

namespace phdslam::reference {

/// Keys: association ("jcbb" | "nn"), metric ("mahalanobis" | "ml"), ic_chi2_quantile,
/// min_associations, mrpt_kdtree_candidates, prune_after_steps, prune_min_associations,
/// symmetrize_covariance.
const params::ParameterTable<MrptEkfSlamOptions>& MrptEkfSlamOptionsTable();

/// Keys: proposal ("motion-model" | "measurement-conditioned"), association, metric,
/// ic_chi2_quantile, new_landmark_log_likelihood (null = derived from the FOV),
/// confirm_associations, tentative_steps, ess_threshold_fraction, resampling ("multinomial" |
/// "residual" | "stratified" | "systematic"), pose_regularisation (the diagonal [qx, qy, qtheta]).
const params::ParameterTable<FastSlamOptions>& FastSlamOptionsTable();

/// Every option by name.
nlohmann::json ToJson(const MrptEkfSlamOptions& options);
nlohmann::json ToJson(const FastSlamOptions& options);

/// Applies the keys of `overrides` (an object) and validates the result. Throws
/// std::invalid_argument naming the key for an unknown key, a wrongly typed or out-of-range value
/// or an invalid result; `options` is unchanged after a throw.
void ApplyJson(const nlohmann::json& overrides, MrptEkfSlamOptions& options);
void ApplyJson(const nlohmann::json& overrides, FastSlamOptions& options);

}  // namespace phdslam::reference
