// Typed readers for parameter overrides given as JSON, with errors that name the parameter.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace phdslam::filters {

/// A finite number.
inline double NumberAt(const nlohmann::json& v, const std::string& key) {
  if (!v.is_number()) throw std::invalid_argument("parameter '" + key + "': expected a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw std::invalid_argument("parameter '" + key + "': not finite");
  return d;
}

/// A whole number of modest size.
inline int IntAt(const nlohmann::json& v, const std::string& key) {
  const double d = NumberAt(v, key);
  if (d != std::floor(d) || std::abs(d) > 1e9) {
    throw std::invalid_argument("parameter '" + key + "': expected an integer");
  }
  return static_cast<int>(d);
}

inline bool BoolAt(const nlohmann::json& v, const std::string& key) {
  if (!v.is_boolean()) throw std::invalid_argument("parameter '" + key + "': expected true/false");
  return v.get<bool>();
}

/// Throws naming the parameter and `what` unless `ok`.
inline void Require(bool ok, const std::string& key, const std::string& what) {
  if (!ok) throw std::invalid_argument("parameter '" + key + "': " + what);
}

}  // namespace phdslam::filters
