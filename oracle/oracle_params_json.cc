#include "oracle/oracle_params_json.h"

#include "src/filters/draw_streams_field.h"

namespace phdslam::oracle {

const params::ParameterTable<OracleParams>& OracleParamsTable() {
  using params::AtLeast;
  using P = OracleParams;
  static const params::ParameterTable<P> table({
      params::IntField<P>(
          "particles", [](auto& p) -> auto& { return p.particles; }, AtLeast(1)),
      params::BoolField<P>(
          "resampling", [](auto& p) -> auto& { return p.resampling; }),
      params::NumberField<P>(
          "ess_threshold", [](auto& p) -> auto& { return p.ess_threshold; }, AtLeast(0.0)),
      params::IntField<P>(
          "ipl_iterations", [](auto& p) -> auto& { return p.ipl_iterations; }, AtLeast(1)),
      params::NumberField<P>(
          "ipl_kl_tolerance", [](auto& p) -> auto& { return p.ipl_kl_tolerance; }, AtLeast(0.0)),
      params::DiagonalField<P, 3>(
          "pose_regularisation", [](auto& p) -> auto& { return p.pose_regularisation; },
          AtLeast(0.0)),
      filters::DrawStreamsField<P>(),
  });
  return table;
}

nlohmann::json ToJson(const OracleParams& params) { return OracleParamsTable().ToJson(params); }

void ApplyJson(const nlohmann::json& overrides, OracleParams& params) {
  OracleParams p = params;
  OracleParamsTable().Apply(overrides, p);
  p.Validate();
  params = p;
}

}  // namespace phdslam::oracle
