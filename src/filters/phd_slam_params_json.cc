#include "src/filters/phd_slam_params_json.h"

#include "src/core/parameter_table.h"
#include "src/filters/draw_streams_field.h"
#include "src/filters/map_params_json.h"

namespace phdslam::filters {

const params::ParameterTable<PhdSlamParams>& PhdSlamParamsTable() {
  using params::AtLeast;
  using P = PhdSlamParams;
  static const params::ParameterTable<P> table(params::Rows<P>({
      {params::IntField<P>(
          "particles", [](auto& p) -> auto& { return p.particles; }, AtLeast(1))},
      params::Embed<P>(
          MapParamsTable(), [](auto& p) -> auto& { return p.map; }),
      {
          params::IntField<P>(
              "max_hypotheses", [](auto& p) -> auto& { return p.max_hypotheses; }, AtLeast(0)),
          params::NumberField<P>(
              "murty_max_cost_gap", [](auto& p) -> auto& { return p.murty_max_cost_gap; },
              AtLeast(0.0)),
          params::BoolField<P>(
              "all_clutter_component", [](auto& p) -> auto& { return p.all_clutter_component; }),
          params::IntField<P>(
              "ipl_iterations", [](auto& p) -> auto& { return p.ipl_iterations; }, AtLeast(1)),
          params::NumberField<P>(
              "ipl_kl_tolerance", [](auto& p) -> auto& { return p.ipl_kl_tolerance; },
              AtLeast(0.0)),
          params::BoolField<P>(
              "resampling", [](auto& p) -> auto& { return p.resampling; }),
          params::EnumField<P, EssThresholdKind>(
              "ess_threshold_kind", [](auto& p) -> auto& { return p.ess_threshold_kind; },
              {{EssThresholdKind::kRelative, "relative"},
               {EssThresholdKind::kAbsolute, "absolute"}}),
          params::NumberField<P>(
              "ess_threshold", [](auto& p) -> auto& { return p.ess_threshold; }, AtLeast(0.0)),
          params::DiagonalField<P, 3>(
              "pose_regularisation", [](auto& p) -> auto& { return p.pose_regularisation; },
              AtLeast(0.0)),
          params::NumberOrAutomaticField<P>(
              "estimate_log_weight_threshold",
              [](auto& p) -> auto& { return p.estimate_log_weight_threshold; }, "from-sensor"),
          params::EnumField<P, RbPhdWeighting>(
              "weighting", [](auto& p) -> auto& { return p.weighting; },
              {{RbPhdWeighting::kPaper46, "paper-46"},
               {RbPhdWeighting::kEmptyMap, "empty-map"},
               {RbPhdWeighting::kSingleFeature, "single-feature"}}),
          params::BoolField<P>(
              "reuse_parent_proposal", [](auto& p) -> auto& { return p.reuse_parent_proposal; }),
          DrawStreamsField<P>(),
      },
  }));
  return table;
}

nlohmann::json ToJson(const PhdSlamParams& params) { return PhdSlamParamsTable().ToJson(params); }

void ApplyJson(const nlohmann::json& overrides, PhdSlamParams& params) {
  PhdSlamParamsTable().Apply(overrides, params);
}

}  // namespace phdslam::filters
