#include "reference/mrpt/mrpt_baseline_params_json.h"

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace phdslam::reference {
namespace {

/// Each value with its text name (association_options.h, fastslam.h).
template <class E>
std::vector<std::pair<E, std::string>> Named(std::initializer_list<E> values) {
  std::vector<std::pair<E, std::string>> names;
  for (E v : values) names.emplace_back(v, ToString(v));
  return names;
}

/// MRPT gates with chi2inv(quantile, 2): a probability in (0, 1).
params::Bounds OpenProbability() { return {0.0, 1.0, true, true}; }

}  // namespace

const params::ParameterTable<MrptEkfSlamOptions>& MrptEkfSlamOptionsTable() {
  using params::AtLeast;
  using O = MrptEkfSlamOptions;
  static const params::ParameterTable<O> table({
      params::EnumField<O, AssociationMethod>(
          "association", [](auto& o) -> auto& { return o.association; },
          Named({AssociationMethod::kJcbb, AssociationMethod::kNearestNeighbour})),
      params::EnumField<O, AssociationMetric>(
          "metric", [](auto& o) -> auto& { return o.metric; },
          Named({AssociationMetric::kMahalanobis, AssociationMetric::kMatchingLikelihood})),
      params::NumberField<O>(
          "ic_chi2_quantile", [](auto& o) -> auto& { return o.ic_chi2_quantile; },
          OpenProbability()),
      params::IntField<O>(
          "min_associations", [](auto& o) -> auto& { return o.min_associations; }, AtLeast(0)),
      params::BoolField<O>(
          "mrpt_kdtree_candidates", [](auto& o) -> auto& { return o.mrpt_kdtree_candidates; }),
      params::IntField<O>(
          "prune_after_steps", [](auto& o) -> auto& { return o.prune_after_steps; }, AtLeast(0)),
      params::IntField<O>(
          "prune_min_associations", [](auto& o) -> auto& { return o.prune_min_associations; },
          AtLeast(1)),
      params::BoolField<O>(
          "symmetrize_covariance", [](auto& o) -> auto& { return o.symmetrize_covariance; }),
  });
  return table;
}

const params::ParameterTable<FastSlamOptions>& FastSlamOptionsTable() {
  using params::AtLeast;
  using O = FastSlamOptions;
  static const params::ParameterTable<O> table({
      params::EnumField<O, FastSlamProposal>(
          "proposal", [](auto& o) -> auto& { return o.proposal; },
          {{FastSlamProposal::kMotionModel, "motion-model"},
           {FastSlamProposal::kMeasurementConditioned, "measurement-conditioned"}}),
      params::EnumField<O, AssociationMethod>(
          "association", [](auto& o) -> auto& { return o.association; },
          Named({AssociationMethod::kJcbb, AssociationMethod::kNearestNeighbour})),
      params::EnumField<O, AssociationMetric>(
          "metric", [](auto& o) -> auto& { return o.metric; },
          Named({AssociationMetric::kMahalanobis, AssociationMetric::kMatchingLikelihood})),
      params::NumberField<O>(
          "ic_chi2_quantile", [](auto& o) -> auto& { return o.ic_chi2_quantile; },
          OpenProbability()),
      params::OptionalNumberField<O>(
          "new_landmark_log_likelihood",
          [](auto& o) -> auto& { return o.new_landmark_log_likelihood; }),
      params::IntField<O>(
          "confirm_associations", [](auto& o) -> auto& { return o.confirm_associations; },
          AtLeast(0)),
      params::IntField<O>(
          "tentative_steps", [](auto& o) -> auto& { return o.tentative_steps; }, AtLeast(1)),
      params::NumberField<O>(
          "ess_threshold_fraction", [](auto& o) -> auto& { return o.ess_threshold_fraction; },
          params::Probability()),
      params::EnumField<O, ResamplingScheme>(
          "resampling", [](auto& o) -> auto& { return o.resampling; },
          Named({ResamplingScheme::kMultinomial, ResamplingScheme::kResidual,
                 ResamplingScheme::kStratified, ResamplingScheme::kSystematic})),
      params::VectorField<O, 3>(
          "pose_regularisation", [](auto& o) -> auto& { return o.pose_regulariser_diag; },
          AtLeast(0.0)),
  });
  return table;
}

nlohmann::json ToJson(const MrptEkfSlamOptions& options) {
  return MrptEkfSlamOptionsTable().ToJson(options);
}

nlohmann::json ToJson(const FastSlamOptions& options) {
  return FastSlamOptionsTable().ToJson(options);
}

void ApplyJson(const nlohmann::json& overrides, MrptEkfSlamOptions& options) {
  MrptEkfSlamOptions o = options;
  MrptEkfSlamOptionsTable().Apply(overrides, o);
  o.Validate();
  options = o;
}

void ApplyJson(const nlohmann::json& overrides, FastSlamOptions& options) {
  FastSlamOptions o = options;
  FastSlamOptionsTable().Apply(overrides, o);
  o.Validate();
  options = o;
}

}  // namespace phdslam::reference
