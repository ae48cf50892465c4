#include "oracle/oracle_params_json.h"

#include "src/filters/draw_streams_field.h"

namespace phdslam::oracle {

const params::ParameterTable<OracleParams>& OracleParamsTable() {
  using params::AtLeast;
  using P = OracleParams;
  static const params::ParameterTable<P> table({
      params::IntField<P>(
          "particles", [](auto& p) -> auto& { return p.particles; }, AtLeast(1))
          .Means("number of particles (set by --particles)"),
      params::BoolField<P>(
          "resampling", [](auto& p) -> auto& { return p.resampling; })
          .Means("resample the particles when the effective sample size falls below ess_threshold"),
      params::NumberField<P>(
          "ess_threshold", [](auto& p) -> auto& { return p.ess_threshold; }, AtLeast(0.0))
          .Means("resample when the effective sample size is at most this fraction of the particle "
                 "count")
          .UsedOnlyWith("resampling", {true}),
      params::IntField<P>(
          "ipl_iterations", [](auto& p) -> auto& { return p.ipl_iterations; }, AtLeast(1))
          .Means("L: most iterations of the iterated posterior linearisation of the pose proposal"),
      params::NumberField<P>(
          "ipl_kl_tolerance", [](auto& p) -> auto& { return p.ipl_kl_tolerance; }, AtLeast(0.0))
          .Means("the iterated posterior linearisation stops when the Kullback-Leibler change "
                 "falls below this")
          .UsedOnlyWithout("ipl_iterations", 1),
      params::DiagonalField<P, 3>(
          "pose_regularisation", [](auto& p) -> auto& { return p.pose_regularisation; },
          AtLeast(0.0))
          .Means("diagonal of Q_n (x, y, heading), the pose noise added once per step before "
                 "propagation"),
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
