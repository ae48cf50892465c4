#include "src/glmb/glmb_slam_params.h"

#include <limits>
#include <optional>

namespace phdslam::glmb {

const params::ParameterTable<GlmbSlamParams>& GlmbSlamParamsTable() {
  using params::Above;
  using params::AtLeast;
  using params::Probability;
  using P = GlmbSlamParams;
  static const params::ParameterTable<P> table(params::Rows<P>({
      {params::IntField<P>(
           "particles", [](auto& p) -> auto& { return p.particles; }, AtLeast(1))
           .Means("number of pose particles, each with its own map (set by --particles)"),
       params::NumberField<P>(
           "survival_probability", [](auto& p) -> auto& { return p.survival_probability; },
           Probability())
           .Means("p_S: probability that a landmark inside the field of view survives a step (1 "
                  "outside)"),
       params::NumberField<P>(
           "gate_probability", [](auto& p) -> auto& { return p.gate_probability; },
           params::Between(0.0, 1.0 - 1e-16))
           .Means("P_G: probability mass inside the measurement gate, giving the chi-square gate "
                  "threshold"),
       params::IntField<P>(
           "gibbs_samples", [](auto& p) -> auto& { return p.gibbs_samples; }, AtLeast(1))
           .Means("H_upd: Gibbs samples of the association per particle and update"),
       params::IntField<P>(
           "max_hypotheses", [](auto& p) -> auto& { return p.max_hypotheses; }, AtLeast(1))
           .Means("H_max: most map hypotheses kept per particle"),
       params::NumberField<P>(
           "hypothesis_prune_threshold",
           [](auto& p) -> auto& { return p.hypothesis_prune_threshold; }, params::Between(0, 1))
           .Means("map hypotheses with a lower weight are dropped"),
       params::BoolField<P>(
           "optimal_start", [](auto& p) -> auto& { return p.optimal_start; })
           .Means("start the Gibbs sampler from the optimal association (else from all misses)"),
       params::EnumField<P, std::optional<models::ClutterSpace>>(
           "clutter_space", [](auto& p) -> auto& { return p.clutter_space; },
           {{std::nullopt, "sensor"}, {models::ClutterSpace::kRangeBearingBox, "range-bearing"}})
           .Means("space of the clutter density: the scenario sensor's (sensor) or uniform over "
                  "the range-bearing box (range-bearing)"),
       params::EnumField<P, BirthRule>("birth_rule", [](auto& p) -> auto& { return p.birth.rule; },
                                       {{BirthRule::kThresholded, "thresholded"},
                                        {BirthRule::kGatesBest, "gates-best"},
                                        {BirthRule::kContinuous, "continuous"}})
           .Means("birth existence of a measurement: by its assignment probability and threshold "
                  "(thresholded), gating with the best hypothesis (gates-best), or continuous"),
       params::NumberField<P>(
           "birth_probability_new", [](auto& p) -> auto& { return p.birth.new_probability; },
           Probability())
           .Means("existence probability of a birth from a measurement that no landmark explains"),
       params::NumberField<P>(
           "birth_probability_existing",
           [](auto& p) -> auto& { return p.birth.existing_probability; }, Probability())
           .Means("existence probability of a birth from a measurement a landmark may explain"),
       params::NumberField<P>(
           "birth_assigned_threshold", [](auto& p) -> auto& { return p.birth.assigned_threshold; },
           Probability())
           .Means("assignment probability at which a measurement counts as explained (birth_rule "
                  "thresholded)")
           .UsedOnlyWith("birth_rule", {"thresholded"}),
       params::EnumField<P, KernelWeight>("kernel_weight",
                                          [](auto& p) -> auto& { return p.kernel_weight; },
                                          {{KernelWeight::kMarginal, "marginal"},
                                           {KernelWeight::kNormaliser, "normaliser"},
                                           {KernelWeight::kImportance, "importance"}})
           .Means("particle weight of the optimal-kernel proposal: marginal (eq. 33), normaliser, "
                  "or importance-corrected"),
       params::EnumField<P, KernelAssociations>(
           "kernel_associations", [](auto& p) -> auto& { return p.kernel_associations; },
           {{KernelAssociations::kAll, "all"}, {KernelAssociations::kBest, "best"}})
           .Means("associations in the optimal-kernel proposal: all sampled ones or only the best"),
       params::EnumField<P, KernelForm>(
           "kernel_form", [](auto& p) -> auto& { return p.kernel_form; },
           {{KernelForm::kCollapse, "collapse"}, {KernelForm::kMixture, "mixture"}})
           .Means("the optimal-kernel pose proposal as one moment-matched Gaussian (collapse) or "
                  "as its mixture"),
       params::NumberField<P>(
           "existence_prune_threshold",
           [](auto& p) -> auto& { return p.existence_prune_threshold; }, Probability())
           .Means("LMB tracks with a lower existence probability are pruned"),
       params::IntField<P>(
           "max_tracks", [](auto& p) -> auto& { return p.max_tracks; }, AtLeast(1))
           .Means("T_max: most LMB tracks kept per particle"),
       params::NumberField<P>(
           "mixture_prune_threshold", [](auto& p) -> auto& { return p.mixture.prune_threshold; },
           Probability())
           .Means("per-track Gaussian components with a lower normalised weight are dropped"),
       params::NumberField<P>(
           "mixture_merge_distance2", [](auto& p) -> auto& { return p.mixture.merge_distance2; },
           AtLeast(0.0))
           .Means("per-track components closer than this squared Mahalanobis distance are merged"),
       params::IntField<P>(
           "mixture_max_components", [](auto& p) -> auto& { return p.mixture.max_components; },
           AtLeast(1))
           .Means("L_max: most Gaussian components per track"),
       params::EnumField<P, ResamplingRule>(
           "resampling", [](auto& p) -> auto& { return p.resampling; },
           {{ResamplingRule::kEveryStep, "every-step"}, {ResamplingRule::kEss, "ess"}})
           .Means("resample the particles every step or when the effective sample size falls below "
                  "ess_threshold"),
       params::EnumField<P, filters::EssThresholdKind>(
           "ess_threshold_kind", [](auto& p) -> auto& { return p.ess_threshold_kind; },
           {{filters::EssThresholdKind::kRelative, "relative"},
            {filters::EssThresholdKind::kAbsolute, "absolute"}})
           .Means("ess_threshold as a fraction of the particle count (relative) or as a particle "
                  "count (absolute)")
           .UsedOnlyWith("resampling", {"ess"}),
       params::NumberField<P>(
           "ess_threshold", [](auto& p) -> auto& { return p.ess_threshold; }, AtLeast(0.0))
           .Means("effective sample size below which the particles are resampled (resampling ess)")
           .UsedOnlyWith("resampling", {"ess"}),
       params::DiagonalField<P, 3>(
           "pose_regularisation", [](auto& p) -> auto& { return p.pose_regularisation; },
           AtLeast(0.0))
           .Means("diagonal of Q_n (x, y, heading), the regulariser of the predicted pose "
                  "covariance")},
  }));
  return table;
}

nlohmann::json ToJson(const GlmbSlamParams& params) { return GlmbSlamParamsTable().ToJson(params); }

void ApplyJson(const nlohmann::json& overrides, GlmbSlamParams& params) {
  GlmbSlamParamsTable().Apply(overrides, params);
}

filters::ParticleFilterParams SkeletonParams(const GlmbSlamParams& params) {
  filters::ParticleFilterParams s;
  s.particles = params.particles;
  s.resampling = true;
  if (params.resampling == ResamplingRule::kEveryStep) {
    s.ess_threshold_kind = filters::EssThresholdKind::kAbsolute;
    s.ess_threshold = std::numeric_limits<double>::infinity();
  } else {
    s.ess_threshold_kind = params.ess_threshold_kind;
    s.ess_threshold = params.ess_threshold;
  }
  s.pose_regularisation = params.pose_regularisation;
  s.reuse_parent_proposal = true;
  return s;
}

}  // namespace phdslam::glmb
