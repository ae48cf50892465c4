#include "src/filters/map_params_json.h"

namespace phdslam::filters {

const params::ParameterTable<phd::MapParams>& MapParamsTable() {
  using params::Above;
  using params::AtLeast;
  using P = phd::MapParams;
  static const params::ParameterTable<P> table({
      params::NumberField<P>(
          "birth_log_weight", [](auto& p) -> auto& { return p.birth_log_weight; })
          .Means("log-weight of the map component born from a measurement"),
      params::NumberField<P>(
          "gate_threshold", [](auto& p) -> auto& { return p.gate_threshold; }, Above(0.0))
          .Means("gate on the squared Mahalanobis distance of a measurement to a map component "
                 "(accepted strictly below)"),
      params::NumberField<P>(
          "prune_log_weight", [](auto& p) -> auto& { return p.prune_log_weight; })
          .Means(
              "map components with a lower log-weight are pruned (the leading one is always kept)"),
      params::NumberField<P>(
          "merge_threshold", [](auto& p) -> auto& { return p.merge_threshold; }, AtLeast(0.0))
          .Means("U: distance below which map components are merged, and the covariance trace "
                 "above which the spread kill applies"),
      params::NumberField<P>(
          "spread_kill_log_weight", [](auto& p) -> auto& { return p.spread_kill_log_weight; })
          .Means("log-weight given to a merged component whose covariance trace exceeds "
                 "merge_threshold"),
      params::BoolField<P>(
          "reference_merge_leading_covariance",
          [](auto& p) -> auto& { return p.reference_merge_leading_covariance; })
          .Means("as the reference code: the merge distance uses the leading component's "
                 "covariance (false: the candidate's, Vo & Ma 2006)"),
      params::BoolField<P>(
          "reference_merge_double_membership",
          [](auto& p) -> auto& { return p.reference_merge_double_membership; })
          .Means("as the reference code: a component may join several merge clusters (false: at "
                 "most one)"),
      params::BoolField<P>(
          "reference_spread_kill", [](auto& p) -> auto& { return p.reference_spread_kill; })
          .Means("as the reference code: merged components spread wider than merge_threshold get "
                 "spread_kill_log_weight (false: kept)"),
      params::BoolField<P>(
          "reference_births_from_ungated_only",
          [](auto& p) -> auto& { return p.reference_births_from_ungated_only; })
          .Means("as the paper: only measurements that gate with no component give births (false: "
                 "every measurement of the previous step)"),
      params::BoolField<P>(
          "reference_omit_missed_detection_mass",
          [](auto& p) -> auto& { return p.reference_omit_missed_detection_mass; })
          .Means("as the paper's eq. 46: the particle weight omits the -sum(pD eta) term of the "
                 "Poisson likelihood (false: include it)"),
  });
  return table;
}

}  // namespace phdslam::filters
