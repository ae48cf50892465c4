#include "src/filters/sc_phd_slam_params.h"

#include <cmath>

#include "src/filters/map_params_json.h"

namespace phdslam::filters {

ScPhdSlamParams::ScPhdSlamParams() {
  map.birth_log_weight = std::log(0.01);
  map.reference_births_from_ungated_only = false;
  map.reference_omit_missed_detection_mass = false;
}

const params::ParameterTable<ScPhdSlamParams>& ScPhdSlamParamsTable() {
  using params::AtLeast;
  using P = ScPhdSlamParams;
  static const params::ParameterTable<P> table(params::Rows<P>({
      {params::IntField<P>(
           "particles", [](auto& p) -> auto& { return p.particles; }, AtLeast(1))
           .Means("N: pose parents kept after pruning (set by --particles)"),
       params::IntField<P>(
           "shotgun", [](auto& p) -> auto& { return p.shotgun; }, AtLeast(1))
           .Means("M: children predicted from every parent (the shotgun factor)")},
      params::Embed<P>(
          MapParamsTable(), [](auto& p) -> auto& { return p.map; }),
      {params::DiagonalField<P, 3>(
           "pose_regularisation", [](auto& p) -> auto& { return p.pose_regularisation; },
           AtLeast(0.0))
           .Means("diagonal of the regularising pose noise Q_n (x, y, heading) added once per step "
                  "before propagation"),
       params::EnumField<P, ScPredictionSampling>(
           "prediction", [](auto& p) -> auto& { return p.prediction; },
           {{ScPredictionSampling::kControlNoise, "control-noise"},
            {ScPredictionSampling::kLinearisedGaussian, "linearised-gaussian"}})
           .Means("how children are drawn: through the control noise (control-noise) or from the "
                  "linearised Gaussian of the motion model"),
       params::BoolField<P>(
           "empty_scan_update", [](auto& p) -> auto& { return p.empty_scan_update; })
           .Means("apply the missed-detection update and weight on scans without measurements")},
  }));
  return table;
}

nlohmann::json ToJson(const ScPhdSlamParams& params) {
  return ScPhdSlamParamsTable().ToJson(params);
}

void ApplyJson(const nlohmann::json& overrides, ScPhdSlamParams& params) {
  ScPhdSlamParamsTable().Apply(overrides, params);
}

}  // namespace phdslam::filters
