#include "src/filters/map_params_json.h"

#include "src/filters/json_fields.h"

namespace phdslam::filters {

void WriteMapParams(const phd::MapParams& p, nlohmann::json& j) {
  j["birth_log_weight"] = p.birth_log_weight;
  j["gate_threshold"] = p.gate_threshold;
  j["prune_log_weight"] = p.prune_log_weight;
  j["merge_threshold"] = p.merge_threshold;
  j["spread_kill_log_weight"] = p.spread_kill_log_weight;
  j["reference_merge_leading_covariance"] = p.reference_merge_leading_covariance;
  j["reference_merge_double_membership"] = p.reference_merge_double_membership;
  j["reference_spread_kill"] = p.reference_spread_kill;
  j["reference_births_from_ungated_only"] = p.reference_births_from_ungated_only;
  j["reference_omit_missed_detection_mass"] = p.reference_omit_missed_detection_mass;
}

bool ApplyMapParam(const std::string& key, const nlohmann::json& v, phd::MapParams& p) {
  if (key == "birth_log_weight") {
    p.birth_log_weight = NumberAt(v, key);
  } else if (key == "gate_threshold") {
    p.gate_threshold = NumberAt(v, key);
    Require(p.gate_threshold > 0, key, "must be > 0");
  } else if (key == "prune_log_weight") {
    p.prune_log_weight = NumberAt(v, key);
  } else if (key == "merge_threshold") {
    p.merge_threshold = NumberAt(v, key);
    Require(p.merge_threshold >= 0, key, "must be >= 0");
  } else if (key == "spread_kill_log_weight") {
    p.spread_kill_log_weight = NumberAt(v, key);
  } else if (key == "reference_merge_leading_covariance") {
    p.reference_merge_leading_covariance = BoolAt(v, key);
  } else if (key == "reference_merge_double_membership") {
    p.reference_merge_double_membership = BoolAt(v, key);
  } else if (key == "reference_spread_kill") {
    p.reference_spread_kill = BoolAt(v, key);
  } else if (key == "reference_births_from_ungated_only") {
    p.reference_births_from_ungated_only = BoolAt(v, key);
  } else if (key == "reference_omit_missed_detection_mass") {
    p.reference_omit_missed_detection_mass = BoolAt(v, key);
  } else {
    return false;
  }
  return true;
}

}  // namespace phdslam::filters
