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
           "particles", [](auto& p) -> auto& { return p.particles; }, AtLeast(1)),
       params::NumberField<P>(
           "survival_probability", [](auto& p) -> auto& { return p.survival_probability; },
           Probability()),
       params::NumberField<P>(
           "gate_probability", [](auto& p) -> auto& { return p.gate_probability; },
           params::Between(0.0, 1.0 - 1e-16)),
       params::IntField<P>(
           "gibbs_samples", [](auto& p) -> auto& { return p.gibbs_samples; }, AtLeast(1)),
       params::IntField<P>(
           "max_hypotheses", [](auto& p) -> auto& { return p.max_hypotheses; }, AtLeast(1)),
       params::NumberField<P>(
           "hypothesis_prune_threshold",
           [](auto& p) -> auto& { return p.hypothesis_prune_threshold; }, params::Between(0, 1)),
       params::BoolField<P>(
           "optimal_start", [](auto& p) -> auto& { return p.optimal_start; }),
       params::EnumField<P, std::optional<models::ClutterSpace>>(
           "clutter_space", [](auto& p) -> auto& { return p.clutter_space; },
           {{std::nullopt, "sensor"}, {models::ClutterSpace::kRangeBearingBox, "range-bearing"}}),
       params::EnumField<P, BirthRule>("birth_rule", [](auto& p) -> auto& { return p.birth.rule; },
                                       {{BirthRule::kThresholded, "thresholded"},
                                        {BirthRule::kGatesBest, "gates-best"},
                                        {BirthRule::kContinuous, "continuous"}}),
       params::NumberField<P>(
           "birth_probability_new", [](auto& p) -> auto& { return p.birth.new_probability; },
           Probability()),
       params::NumberField<P>(
           "birth_probability_existing",
           [](auto& p) -> auto& { return p.birth.existing_probability; }, Probability()),
       params::NumberField<P>(
           "birth_assigned_threshold", [](auto& p) -> auto& { return p.birth.assigned_threshold; },
           Probability()),
       params::EnumField<P, KernelWeight>("kernel_weight",
                                          [](auto& p) -> auto& { return p.kernel_weight; },
                                          {{KernelWeight::kMarginal, "marginal"},
                                           {KernelWeight::kNormaliser, "normaliser"},
                                           {KernelWeight::kImportance, "importance"}}),
       params::EnumField<P, KernelAssociations>(
           "kernel_associations", [](auto& p) -> auto& { return p.kernel_associations; },
           {{KernelAssociations::kAll, "all"}, {KernelAssociations::kBest, "best"}}),
       params::EnumField<P, KernelForm>(
           "kernel_form", [](auto& p) -> auto& { return p.kernel_form; },
           {{KernelForm::kCollapse, "collapse"}, {KernelForm::kMixture, "mixture"}}),
       params::NumberField<P>(
           "existence_prune_threshold",
           [](auto& p) -> auto& { return p.existence_prune_threshold; }, Probability()),
       params::IntField<P>(
           "max_tracks", [](auto& p) -> auto& { return p.max_tracks; }, AtLeast(1)),
       params::NumberField<P>(
           "mixture_prune_threshold", [](auto& p) -> auto& { return p.mixture.prune_threshold; },
           Probability()),
       params::NumberField<P>(
           "mixture_merge_distance2", [](auto& p) -> auto& { return p.mixture.merge_distance2; },
           AtLeast(0.0)),
       params::IntField<P>(
           "mixture_max_components", [](auto& p) -> auto& { return p.mixture.max_components; },
           AtLeast(1)),
       params::EnumField<P, ResamplingRule>(
           "resampling", [](auto& p) -> auto& { return p.resampling; },
           {{ResamplingRule::kEveryStep, "every-step"}, {ResamplingRule::kEss, "ess"}}),
       params::EnumField<P, filters::EssThresholdKind>(
           "ess_threshold_kind", [](auto& p) -> auto& { return p.ess_threshold_kind; },
           {{filters::EssThresholdKind::kRelative, "relative"},
            {filters::EssThresholdKind::kAbsolute, "absolute"}}),
       params::NumberField<P>(
           "ess_threshold", [](auto& p) -> auto& { return p.ess_threshold; }, AtLeast(0.0)),
       params::DiagonalField<P, 3>(
           "pose_regularisation", [](auto& p) -> auto& { return p.pose_regularisation; },
           AtLeast(0.0))},
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
