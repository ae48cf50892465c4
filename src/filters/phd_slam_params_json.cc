#include "src/filters/phd_slam_params_json.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "src/filters/json_fields.h"
#include "src/filters/map_params_json.h"

namespace phdslam::filters {

nlohmann::json ToJson(const PhdSlamParams& p) {
  nlohmann::json j;
  j["particles"] = p.particles;
  WriteMapParams(p.map, j);
  j["max_hypotheses"] = p.max_hypotheses;
  j["murty_max_cost_gap"] = p.murty_max_cost_gap;
  j["all_clutter_component"] = p.all_clutter_component;
  j["ipl_iterations"] = p.ipl_iterations;
  j["ipl_kl_tolerance"] = p.ipl_kl_tolerance;
  j["resampling"] = p.resampling;
  j["ess_threshold_kind"] =
      p.ess_threshold_kind == EssThresholdKind::kRelative ? "relative" : "absolute";
  j["ess_threshold"] = p.ess_threshold;
  j["pose_regularisation"] = {p.pose_regularisation(0, 0), p.pose_regularisation(1, 1),
                              p.pose_regularisation(2, 2)};
  if (std::isnan(p.estimate_log_weight_threshold)) {
    j["estimate_log_weight_threshold"] = "from-sensor";
  } else {
    j["estimate_log_weight_threshold"] = p.estimate_log_weight_threshold;
  }
  j["reuse_parent_proposal"] = p.reuse_parent_proposal;
  return j;
}

void ApplyJson(const nlohmann::json& overrides, PhdSlamParams& p) {
  if (!overrides.is_object()) throw std::invalid_argument("parameters: expected an object");
  for (const auto& [key, v] : overrides.items()) {
    if (key == "particles") {
      p.particles = IntAt(v, key);
      Require(p.particles >= 1, key, "must be >= 1");
    } else if (ApplyMapParam(key, v, p.map)) {
      // a GM-PHD map parameter
    } else if (key == "max_hypotheses") {
      p.max_hypotheses = IntAt(v, key);
      Require(p.max_hypotheses >= 0, key, "must be >= 0");
    } else if (key == "murty_max_cost_gap") {
      p.murty_max_cost_gap = NumberAt(v, key);
      Require(p.murty_max_cost_gap >= 0, key, "must be >= 0");
    } else if (key == "all_clutter_component") {
      p.all_clutter_component = BoolAt(v, key);
    } else if (key == "ipl_iterations") {
      p.ipl_iterations = IntAt(v, key);
      Require(p.ipl_iterations >= 1, key, "must be >= 1");
    } else if (key == "ipl_kl_tolerance") {
      p.ipl_kl_tolerance = NumberAt(v, key);
      Require(p.ipl_kl_tolerance >= 0, key, "must be >= 0");
    } else if (key == "resampling") {
      p.resampling = BoolAt(v, key);
    } else if (key == "ess_threshold_kind") {
      Require(v.is_string(), key, "expected \"relative\" or \"absolute\"");
      const std::string s = v.get<std::string>();
      Require(s == "relative" || s == "absolute", key, "expected \"relative\" or \"absolute\"");
      p.ess_threshold_kind = s == "relative" ? EssThresholdKind::kRelative : EssThresholdKind::kAbsolute;
    } else if (key == "ess_threshold") {
      p.ess_threshold = NumberAt(v, key);
      Require(p.ess_threshold >= 0, key, "must be >= 0");
    } else if (key == "pose_regularisation") {
      Require(v.is_array() && v.size() == 3, key, "expected [qx, qy, qtheta]");
      for (int i = 0; i < 3; ++i) {
        p.pose_regularisation(i, i) = NumberAt(v[i], key);
        Require(p.pose_regularisation(i, i) >= 0, key, "entries must be >= 0");
      }
    } else if (key == "estimate_log_weight_threshold") {
      if (v.is_string() && v.get<std::string>() == "from-sensor") {
        p.estimate_log_weight_threshold = std::nan("");
      } else {
        p.estimate_log_weight_threshold = NumberAt(v, key);
      }
    } else if (key == "reuse_parent_proposal") {
      p.reuse_parent_proposal = BoolAt(v, key);
    } else {
      throw std::invalid_argument("unknown parameter '" + key + "'");
    }
  }
}

}  // namespace phdslam::filters
