#include "reference/ceres/smoother_params_json.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace phdslam::reference {
namespace {

[[noreturn]] void Fail(const std::string& key, const std::string& what) {
  throw std::invalid_argument("smoother parameter '" + key + "': " + what);
}

double NumberAt(const nlohmann::json& v, const std::string& key) {
  if (!v.is_number()) Fail(key, "expected a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) Fail(key, "expected a finite number");
  return d;
}

int IntAt(const nlohmann::json& v, const std::string& key) {
  const double d = NumberAt(v, key);
  if (d != std::floor(d) || std::abs(d) > 1e9) Fail(key, "expected an integer");
  return static_cast<int>(d);
}

bool BoolAt(const nlohmann::json& v, const std::string& key) {
  if (!v.is_boolean()) Fail(key, "expected true or false");
  return v.get<bool>();
}

std::string StringAt(const nlohmann::json& v, const std::string& key) {
  if (!v.is_string()) Fail(key, "expected a string");
  return v.get<std::string>();
}

OdometryNoiseFloor FloorAt(const nlohmann::json& v, const std::string& key) {
  if (!v.is_array() || v.size() != 2) Fail(key, "expected [position_std, heading_std]");
  return {NumberAt(v[0], key), NumberAt(v[1], key)};
}

const char* AssociationName(AssociationMode m) {
  switch (m) {
    case AssociationMode::kKnown:
      return "known";
    case AssociationMode::kFilter:
      return "filter";
    case AssociationMode::kUnknown:
      return "unknown";
  }
  return "known";
}

}  // namespace

nlohmann::json ToJson(const SmootherOptions& o) {
  nlohmann::json j;
  j["association"] = AssociationName(o.association);
  j["max_iterations"] = o.max_iterations;
  j["function_tolerance"] = o.function_tolerance;
  j["intermediate_function_tolerance"] = o.intermediate_function_tolerance;
  j["compute_covariances"] = o.compute_covariances;
  j["linear_solver"] = o.linear_solver == SparseLinearSolver::kSparseSchur
                           ? "sparse_schur"
                           : "sparse_normal_cholesky";
  j["num_threads"] = o.num_threads;
  j["odometry_residual"] =
      o.odometry_residual == OdometryResidual::kPoseSpace ? "pose_space" : "control_space";
  j["odometry_floor"] = {o.odometry_floor.position_std, o.odometry_floor.heading_std};
  j["warm_start_floor"] = {o.warm_start_floor.position_std, o.warm_start_floor.heading_std};
  j["initial_pass_solve_steps"] = o.initial_pass_solve_steps;
  j["reassociation_rounds"] = o.reassociation_rounds;
  j["gate_chi2"] = o.gate_chi2;
  j["min_observations"] = o.min_observations;
  j["merge_position_std"] = o.merge_position_std;
  j["min_detection_ratio"] = o.min_detection_ratio;
  j["robust_loss"] = o.robust_loss;
  j["robust_scale"] = o.robust_scale;
  j["filter_label_distance"] = o.filter_label_distance;
  return j;
}

void ApplyJson(const nlohmann::json& overrides, SmootherOptions& options) {
  if (!overrides.is_object()) {
    throw std::invalid_argument("smoother parameters: expected a JSON object");
  }
  SmootherOptions o = options;
  for (const auto& [key, v] : overrides.items()) {
    if (key == "association") {
      Fail(key,
           "fixed by the estimator's name (smoother-known, smoother-filter, smoother-unknown)");
    } else if (key == "max_iterations") {
      o.max_iterations = IntAt(v, key);
    } else if (key == "function_tolerance") {
      o.function_tolerance = NumberAt(v, key);
    } else if (key == "intermediate_function_tolerance") {
      o.intermediate_function_tolerance = NumberAt(v, key);
    } else if (key == "compute_covariances") {
      o.compute_covariances = BoolAt(v, key);
    } else if (key == "linear_solver") {
      const std::string s = StringAt(v, key);
      if (s == "sparse_normal_cholesky") {
        o.linear_solver = SparseLinearSolver::kSparseNormalCholesky;
      } else if (s == "sparse_schur") {
        o.linear_solver = SparseLinearSolver::kSparseSchur;
      } else {
        Fail(key, "expected \"sparse_normal_cholesky\" or \"sparse_schur\", got \"" + s + "\"");
      }
    } else if (key == "num_threads") {
      o.num_threads = IntAt(v, key);
    } else if (key == "odometry_residual") {
      const std::string s = StringAt(v, key);
      if (s == "control_space") {
        o.odometry_residual = OdometryResidual::kControlSpace;
      } else if (s == "pose_space") {
        o.odometry_residual = OdometryResidual::kPoseSpace;
      } else {
        Fail(key, "expected \"control_space\" or \"pose_space\", got \"" + s + "\"");
      }
    } else if (key == "odometry_floor") {
      o.odometry_floor = FloorAt(v, key);
    } else if (key == "warm_start_floor") {
      o.warm_start_floor = FloorAt(v, key);
    } else if (key == "initial_pass_solve_steps") {
      o.initial_pass_solve_steps = IntAt(v, key);
    } else if (key == "reassociation_rounds") {
      o.reassociation_rounds = IntAt(v, key);
    } else if (key == "gate_chi2") {
      o.gate_chi2 = NumberAt(v, key);
    } else if (key == "min_observations") {
      o.min_observations = IntAt(v, key);
    } else if (key == "merge_position_std") {
      o.merge_position_std = NumberAt(v, key);
    } else if (key == "min_detection_ratio") {
      o.min_detection_ratio = NumberAt(v, key);
    } else if (key == "robust_loss") {
      o.robust_loss = StringAt(v, key);
    } else if (key == "robust_scale") {
      o.robust_scale = NumberAt(v, key);
    } else if (key == "filter_label_distance") {
      o.filter_label_distance = NumberAt(v, key);
    } else {
      const nlohmann::json defaults = ToJson(SmootherOptions{});
      std::string known;
      for (auto it = defaults.begin(); it != defaults.end(); ++it) {
        if (it.key() == "association") continue;
        known += known.empty() ? it.key() : ", " + it.key();
      }
      Fail(key, "unknown parameter (known: " + known + ")");
    }
  }
  try {
    o.Validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("smoother parameters: ") + e.what());
  }
  options = std::move(o);
}

}  // namespace phdslam::reference
