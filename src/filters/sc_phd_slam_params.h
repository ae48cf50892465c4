// Parameters of single-cluster PHD SLAM (sc_phd_slam.h) and their parameter table.
#pragma once

#include <nlohmann/json.hpp>

#include "src/core/parameter_table.h"
#include "src/core/types.h"
#include "src/phd/map_params.h"

namespace phdslam::filters {

/// How a child's pose is drawn from its parent.
enum class ScPredictionSampling {
  kControlNoise,        ///< u + N(0, Q_u) per sub-interval through the motion model
  kLinearisedGaussian,  ///< one draw from the linearised propagated Gaussian
};

struct ScPhdSlamParams {
  /// N: parents kept after pruning.
  int particles = 1;
  /// M: children predicted from every parent ("shotgun" factor).
  int shotgun = 4;
  /// GM-PHD map options. Defaults differ from PhdSlamParams in three places (set by the
  /// constructor): birth_log_weight = ln 0.01, births from every measurement of the previous
  /// step, and the missed-detection mass -sum pD w kept in the parent weight.
  phd::MapParams map;
  /// Q_n: regularising pose noise, once per step before propagation (docs/algorithms/models.md
  /// section 2.4).
  Mat3 pose_regularisation = Vec3(1e-9, 1e-9, 1e-18).asDiagonal();
  ScPredictionSampling prediction = ScPredictionSampling::kControlNoise;
  /// Apply the missed-detection update and weight on scans without measurements.
  bool empty_scan_update = true;

  ScPhdSlamParams();
};

/// The parameter table: every parameter by name (flat object; matrices as arrays of their
/// diagonal), with the checks applied to overrides.
const params::ParameterTable<ScPhdSlamParams>& ScPhdSlamParamsTable();

/// Every parameter by name.
nlohmann::json ToJson(const ScPhdSlamParams& params);

/// Applies the keys of `overrides`. Throws std::invalid_argument naming the key when it is unknown
/// or its value has the wrong type or is out of range.
void ApplyJson(const nlohmann::json& overrides, ScPhdSlamParams& params);

}  // namespace phdslam::filters
