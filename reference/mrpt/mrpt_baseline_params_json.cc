#include "reference/mrpt/mrpt_baseline_params_json.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace phdslam::reference {
namespace {

std::string Field(const std::string& owner, const std::string& key) {
  return owner + " parameter '" + key + "'";
}

double NumberAt(const nlohmann::json& v, const std::string& field) {
  if (!v.is_number()) throw std::invalid_argument(field + ": expected a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw std::invalid_argument(field + ": expected a finite number");
  return d;
}

int IntAt(const nlohmann::json& v, const std::string& field) {
  const double d = NumberAt(v, field);
  if (d != std::floor(d) || std::abs(d) > 1e9) {
    throw std::invalid_argument(field + ": expected an integer");
  }
  return static_cast<int>(d);
}

bool BoolAt(const nlohmann::json& v, const std::string& field) {
  if (!v.is_boolean()) throw std::invalid_argument(field + ": expected true or false");
  return v.get<bool>();
}

std::string StringAt(const nlohmann::json& v, const std::string& field) {
  if (!v.is_string()) throw std::invalid_argument(field + ": expected a string");
  return v.get<std::string>();
}

void RequireObject(const nlohmann::json& overrides, const std::string& owner) {
  if (!overrides.is_object()) {
    throw std::invalid_argument(owner + " parameters: expected a JSON object");
  }
}

}  // namespace

nlohmann::json ToJson(const MrptEkfSlamOptions& o) {
  nlohmann::json j;
  j["association"] = ToString(o.association);
  j["metric"] = ToString(o.metric);
  j["ic_chi2_quantile"] = o.ic_chi2_quantile;
  j["min_associations"] = o.min_associations;
  j["mrpt_kdtree_candidates"] = o.mrpt_kdtree_candidates;
  j["prune_after_steps"] = o.prune_after_steps;
  j["prune_min_associations"] = o.prune_min_associations;
  j["symmetrize_covariance"] = o.symmetrize_covariance;
  return j;
}

nlohmann::json ToJson(const FastSlamOptions& o) {
  nlohmann::json j;
  j["proposal"] =
      o.proposal == FastSlamProposal::kMotionModel ? "motion-model" : "measurement-conditioned";
  j["association"] = ToString(o.association);
  j["metric"] = ToString(o.metric);
  j["ic_chi2_quantile"] = o.ic_chi2_quantile;
  j["new_landmark_log_likelihood"] = o.new_landmark_log_likelihood
                                         ? nlohmann::json(*o.new_landmark_log_likelihood)
                                         : nlohmann::json(nullptr);
  j["confirm_associations"] = o.confirm_associations;
  j["tentative_steps"] = o.tentative_steps;
  j["ess_threshold_fraction"] = o.ess_threshold_fraction;
  j["resampling"] = ToString(o.resampling);
  j["pose_regularisation"] = {o.pose_regulariser_diag(0), o.pose_regulariser_diag(1),
                              o.pose_regulariser_diag(2)};
  return j;
}

void ApplyJson(const nlohmann::json& overrides, MrptEkfSlamOptions& options) {
  const std::string owner = "mrpt-ekf";
  RequireObject(overrides, owner);
  MrptEkfSlamOptions o = options;
  for (const auto& [key, v] : overrides.items()) {
    const std::string field = Field(owner, key);
    if (key == "association") {
      o.association = ParseAssociationMethod(StringAt(v, field), field);
    } else if (key == "metric") {
      o.metric = ParseAssociationMetric(StringAt(v, field), field);
    } else if (key == "ic_chi2_quantile") {
      o.ic_chi2_quantile = NumberAt(v, field);
    } else if (key == "min_associations") {
      o.min_associations = IntAt(v, field);
    } else if (key == "mrpt_kdtree_candidates") {
      o.mrpt_kdtree_candidates = BoolAt(v, field);
    } else if (key == "prune_after_steps") {
      o.prune_after_steps = IntAt(v, field);
    } else if (key == "prune_min_associations") {
      o.prune_min_associations = IntAt(v, field);
    } else if (key == "symmetrize_covariance") {
      o.symmetrize_covariance = BoolAt(v, field);
    } else {
      throw std::invalid_argument(field + ": unknown (known: " + ToJson(options).dump() + ")");
    }
  }
  o.Validate();
  options = o;
}

void ApplyJson(const nlohmann::json& overrides, FastSlamOptions& options) {
  const std::string owner = "fastslam";
  RequireObject(overrides, owner);
  FastSlamOptions o = options;
  for (const auto& [key, v] : overrides.items()) {
    const std::string field = Field(owner, key);
    if (key == "proposal") {
      const std::string s = StringAt(v, field);
      if (s == "motion-model") {
        o.proposal = FastSlamProposal::kMotionModel;
      } else if (s == "measurement-conditioned") {
        o.proposal = FastSlamProposal::kMeasurementConditioned;
      } else {
        throw std::invalid_argument(field +
                                    ": expected \"motion-model\" or \"measurement-conditioned\"");
      }
    } else if (key == "association") {
      o.association = ParseAssociationMethod(StringAt(v, field), field);
    } else if (key == "metric") {
      o.metric = ParseAssociationMetric(StringAt(v, field), field);
    } else if (key == "ic_chi2_quantile") {
      o.ic_chi2_quantile = NumberAt(v, field);
    } else if (key == "new_landmark_log_likelihood") {
      if (v.is_null()) {
        o.new_landmark_log_likelihood.reset();
      } else {
        o.new_landmark_log_likelihood = NumberAt(v, field);
      }
    } else if (key == "confirm_associations") {
      o.confirm_associations = IntAt(v, field);
    } else if (key == "tentative_steps") {
      o.tentative_steps = IntAt(v, field);
    } else if (key == "ess_threshold_fraction") {
      o.ess_threshold_fraction = NumberAt(v, field);
    } else if (key == "resampling") {
      o.resampling = ParseResamplingScheme(StringAt(v, field), field);
    } else if (key == "pose_regularisation") {
      if (!v.is_array() || v.size() != 3) {
        throw std::invalid_argument(field + ": expected the diagonal [qx, qy, qtheta]");
      }
      for (int i = 0; i < 3; ++i) {
        o.pose_regulariser_diag(i) = NumberAt(v[static_cast<std::size_t>(i)], field);
      }
    } else {
      throw std::invalid_argument(field + ": unknown (known: " + ToJson(options).dump() + ")");
    }
  }
  o.Validate();
  options = o;
}

}  // namespace phdslam::reference
