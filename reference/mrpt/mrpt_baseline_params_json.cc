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
          Named({AssociationMethod::kJcbb, AssociationMethod::kNearestNeighbour}))
          .Means(
              "MRPT's data association: joint compatibility branch and bound or nearest neighbour"),
      params::EnumField<O, AssociationMetric>(
          "metric", [](auto& o) -> auto& { return o.metric; },
          Named({AssociationMetric::kMahalanobis, AssociationMetric::kMatchingLikelihood}))
          .Means("distance of MRPT's association: Mahalanobis or matching likelihood"),
      params::NumberField<O>(
          "ic_chi2_quantile", [](auto& o) -> auto& { return o.ic_chi2_quantile; },
          OpenProbability())
          .Means("individual-compatibility gate: a pairing is a candidate below chi2inv(quantile, "
                 "2); unmatched measurements become landmarks"),
      params::IntField<O>(
          "min_associations", [](auto& o) -> auto& { return o.min_associations; }, AtLeast(0))
          .Means("mrpt-ekf-postprocessed: the map keeps landmarks associated at least this many "
                 "times"),
      params::BoolField<O>(
          "mrpt_kdtree_candidates", [](auto& o) -> auto& { return o.mrpt_kdtree_candidates; })
          .Means("look up association candidates with MRPT's KD-tree, which can hide the right one "
                 "(false: test every landmark)"),
      params::IntField<O>(
          "prune_after_steps", [](auto& o) -> auto& { return o.prune_after_steps; }, AtLeast(0))
          .Means("track deletion (not in MRPT): a landmark this many steps old with too few "
                 "associations is removed (0: off)"),
      params::IntField<O>(
          "prune_min_associations", [](auto& o) -> auto& { return o.prune_min_associations; },
          AtLeast(1))
          .Means("track deletion: associations a landmark needs by prune_after_steps to be kept")
          .UsedOnlyWithout("prune_after_steps", 0),
      params::BoolField<O>(
          "symmetrize_covariance", [](auto& o) -> auto& { return o.symmetrize_covariance; })
          .Means("symmetrise the covariance after every step (not in MRPT, whose update lets it "
                 "drift indefinite)"),
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
           {FastSlamProposal::kMeasurementConditioned, "measurement-conditioned"}})
          .Means("pose proposal: the motion model (fastslam1) or conditioned on the measurements "
                 "(fastslam2)"),
      params::EnumField<O, AssociationMethod>(
          "association", [](auto& o) -> auto& { return o.association; },
          Named({AssociationMethod::kJcbb, AssociationMethod::kNearestNeighbour}))
          .Means("per-particle data association of MRPT's routine"),
      params::EnumField<O, AssociationMetric>(
          "metric", [](auto& o) -> auto& { return o.metric; },
          Named({AssociationMetric::kMahalanobis, AssociationMetric::kMatchingLikelihood}))
          .Means("distance of the per-particle association: matching likelihood or Mahalanobis"),
      params::NumberField<O>(
          "ic_chi2_quantile", [](auto& o) -> auto& { return o.ic_chi2_quantile; },
          OpenProbability())
          .Means("new-landmark gate: a measurement is a candidate for a landmark below "
                 "chi2inv(quantile, 2)"),
      params::OptionalNumberField<O>(
          "new_landmark_log_likelihood",
          [](auto& o) -> auto& { return o.new_landmark_log_likelihood; })
          .Means("log-likelihood credited to a measurement that creates a landmark (null: uniform "
                 "over the field of view)"),
      params::IntField<O>(
          "confirm_associations", [](auto& o) -> auto& { return o.confirm_associations; },
          AtLeast(0))
          .Means("associations after creation that confirm a landmark into the map"),
      params::IntField<O>(
          "tentative_steps", [](auto& o) -> auto& { return o.tentative_steps; }, AtLeast(1))
          .Means("steps after its creation at which an unconfirmed landmark is removed"),
      params::NumberField<O>(
          "ess_threshold_fraction", [](auto& o) -> auto& { return o.ess_threshold_fraction; },
          params::Probability())
          .Means("resample when the effective sample size is at most this fraction of the particle "
                 "count"),
      params::EnumField<O, ResamplingScheme>(
          "resampling", [](auto& o) -> auto& { return o.resampling; },
          Named({ResamplingScheme::kMultinomial, ResamplingScheme::kResidual,
                 ResamplingScheme::kStratified, ResamplingScheme::kSystematic}))
          .Means("resampling scheme of MRPT's particle filter"),
      params::VectorField<O, 3>(
          "pose_regularisation", [](auto& o) -> auto& { return o.pose_regulariser_diag; },
          AtLeast(0.0))
          .Means("diagonal of the regulariser (x, y, heading) added to the predicted pose "
                 "covariance once per step"),
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
