#include "src/filters/map_params_json.h"

namespace phdslam::filters {

const params::ParameterTable<phd::MapParams>& MapParamsTable() {
  using params::Above;
  using params::AtLeast;
  using P = phd::MapParams;
  static const params::ParameterTable<P> table({
      params::NumberField<P>(
          "birth_log_weight", [](auto& p) -> auto& { return p.birth_log_weight; }),
      params::NumberField<P>(
          "gate_threshold", [](auto& p) -> auto& { return p.gate_threshold; }, Above(0.0)),
      params::NumberField<P>(
          "prune_log_weight", [](auto& p) -> auto& { return p.prune_log_weight; }),
      params::NumberField<P>(
          "merge_threshold", [](auto& p) -> auto& { return p.merge_threshold; }, AtLeast(0.0)),
      params::NumberField<P>(
          "spread_kill_log_weight", [](auto& p) -> auto& { return p.spread_kill_log_weight; }),
      params::BoolField<P>(
          "reference_merge_leading_covariance",
          [](auto& p) -> auto& { return p.reference_merge_leading_covariance; }),
      params::BoolField<P>(
          "reference_merge_double_membership",
          [](auto& p) -> auto& { return p.reference_merge_double_membership; }),
      params::BoolField<P>(
          "reference_spread_kill", [](auto& p) -> auto& { return p.reference_spread_kill; }),
      params::BoolField<P>(
          "reference_births_from_ungated_only",
          [](auto& p) -> auto& { return p.reference_births_from_ungated_only; }),
      params::BoolField<P>(
          "reference_omit_missed_detection_mass",
          [](auto& p) -> auto& { return p.reference_omit_missed_detection_mass; }),
  });
  return table;
}

}  // namespace phdslam::filters
