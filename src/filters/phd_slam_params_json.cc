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
           "particles", [](auto& p) -> auto& { return p.particles; }, AtLeast(1))
           .Means("number of particles (set by --particles)")},
      params::Embed<P>(
          MapParamsTable(), [](auto& p) -> auto& { return p.map; }),
      {
          params::IntField<P>(
              "max_hypotheses", [](auto& p) -> auto& { return p.max_hypotheses; }, AtLeast(0))
              .Means("most Murty association hypotheses in the Gaussian-mixture importance density "
                     "(J-bar); 0 gives the transition density of PHD-SLAM 1.0"),
          params::NumberField<P>(
              "murty_max_cost_gap", [](auto& p) -> auto& { return p.murty_max_cost_gap; },
              AtLeast(0.0))
              .Means("Murty early stop: hypotheses whose total cost exceeds the best one's by more "
                     "than this are not enumerated")
              .UsedOnlyWithout("max_hypotheses", 0),
          params::BoolField<P>(
              "all_clutter_component", [](auto& p) -> auto& { return p.all_clutter_component; })
              .Means("as the reference code: add an all-clutter component (prior mean and "
                     "covariance) to the proposal mixture"),
          params::IntField<P>(
              "ipl_iterations", [](auto& p) -> auto& { return p.ipl_iterations; }, AtLeast(1))
              .Means("most iterations of the iterated posterior linearisation of each proposal "
                     "component"),
          params::NumberField<P>(
              "ipl_kl_tolerance", [](auto& p) -> auto& { return p.ipl_kl_tolerance; }, AtLeast(0.0))
              .Means("the iterated posterior linearisation stops when the Kullback-Leibler change "
                     "falls below this")
              .UsedOnlyWithout("ipl_iterations", 1),
          params::BoolField<P>(
              "resampling", [](auto& p) -> auto& { return p.resampling; })
              .Means("resample the particles when the effective sample size falls below "
                     "ess_threshold"),
          params::EnumField<P, EssThresholdKind>(
              "ess_threshold_kind", [](auto& p) -> auto& { return p.ess_threshold_kind; },
              {{EssThresholdKind::kRelative, "relative"},
               {EssThresholdKind::kAbsolute, "absolute"}})
              .Means("ess_threshold as a fraction of the particle count (relative) or as a "
                     "particle count (absolute)")
              .UsedOnlyWith("resampling", {true}),
          params::NumberField<P>(
              "ess_threshold", [](auto& p) -> auto& { return p.ess_threshold; }, AtLeast(0.0))
              .Means("effective sample size below which the particles are resampled (0 disables)")
              .UsedOnlyWith("resampling", {true}),
          params::DiagonalField<P, 3>(
              "pose_regularisation", [](auto& p) -> auto& { return p.pose_regularisation; },
              AtLeast(0.0))
              .Means("diagonal of the regularising pose noise (x, y, heading) added once per step "
                     "before propagation"),
          params::NumberOrAutomaticField<P>(
              "estimate_log_weight_threshold",
              [](auto& p) -> auto& { return p.estimate_log_weight_threshold; }, "from-sensor")
              .Means("map estimate keeps components with log-weight above this; from-sensor "
                     "derives ln((1 - pD)^2) from the nominal pD"),
          params::EnumField<P, RbPhdWeighting>("weighting",
                                               [](auto& p) -> auto& { return p.weighting; },
                                               {{RbPhdWeighting::kPaper46, "paper-46"},
                                                {RbPhdWeighting::kEmptyMap, "empty-map"},
                                                {RbPhdWeighting::kSingleFeature, "single-feature"}})
              .Means("particle weight: the paper's eq. 46 (paper-46) or Mullane et al.'s empty-map "
                     "or single-feature strategy"),
          params::BoolField<P>(
              "reuse_parent_proposal", [](auto& p) -> auto& { return p.reuse_parent_proposal; })
              .Means("copies of one resampled parent share one proposal (a speed-up of the "
                     "reference code, results unchanged)"),
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
