#include "oracle/oracle_params_json.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace phdslam::oracle {
namespace {

double NumberAt(const nlohmann::json& v, const std::string& key) {
  if (!v.is_number()) {
    throw std::invalid_argument("oracle parameter '" + key + "': expected a number");
  }
  const double d = v.get<double>();
  if (!std::isfinite(d)) {
    throw std::invalid_argument("oracle parameter '" + key + "': expected a finite number");
  }
  return d;
}

int IntAt(const nlohmann::json& v, const std::string& key) {
  const double d = NumberAt(v, key);
  if (d != std::floor(d) || std::abs(d) > 1e9) {
    throw std::invalid_argument("oracle parameter '" + key + "': expected an integer");
  }
  return static_cast<int>(d);
}

bool BoolAt(const nlohmann::json& v, const std::string& key) {
  if (!v.is_boolean()) {
    throw std::invalid_argument("oracle parameter '" + key + "': expected true or false");
  }
  return v.get<bool>();
}

}  // namespace

nlohmann::json ToJson(const OracleParams& p) {
  nlohmann::json j;
  j["particles"] = p.particles;
  j["resampling"] = p.resampling;
  j["ess_threshold"] = p.ess_threshold;
  j["ipl_iterations"] = p.ipl_iterations;
  j["ipl_kl_tolerance"] = p.ipl_kl_tolerance;
  j["pose_regularisation"] = {p.pose_regularisation(0, 0), p.pose_regularisation(1, 1),
                              p.pose_regularisation(2, 2)};
  return j;
}

void ApplyJson(const nlohmann::json& overrides, OracleParams& params) {
  if (!overrides.is_object()) {
    throw std::invalid_argument("oracle parameters: expected a JSON object");
  }
  OracleParams p = params;
  for (const auto& [key, v] : overrides.items()) {
    if (key == "particles") {
      p.particles = IntAt(v, key);
    } else if (key == "resampling") {
      p.resampling = BoolAt(v, key);
    } else if (key == "ess_threshold") {
      p.ess_threshold = NumberAt(v, key);
    } else if (key == "ipl_iterations") {
      p.ipl_iterations = IntAt(v, key);
    } else if (key == "ipl_kl_tolerance") {
      p.ipl_kl_tolerance = NumberAt(v, key);
    } else if (key == "pose_regularisation") {
      if (!v.is_array() || v.size() != 3) {
        throw std::invalid_argument("oracle parameter '" + key +
                                    "': expected the diagonal [qx, qy, qtheta]");
      }
      Vec3 d;
      for (int i = 0; i < 3; ++i) {
        d(i) = NumberAt(v[static_cast<std::size_t>(i)], key);
        if (d(i) < 0.0) {
          throw std::invalid_argument("oracle parameter '" + key + "': entries must be >= 0");
        }
      }
      p.pose_regularisation = d.asDiagonal();
    } else {
      throw std::invalid_argument(
          "unknown oracle parameter '" + key +
          "' (known: particles, resampling, ess_threshold, ipl_iterations, ipl_kl_tolerance, "
          "pose_regularisation)");
    }
  }
  p.Validate();
  params = p;
}

}  // namespace phdslam::oracle
