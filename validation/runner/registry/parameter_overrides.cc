#include "validation/runner/registry/parameter_overrides.h"

#include <cmath>
#include <stdexcept>

#include "src/core/parameter_table.h"
#include "validation/runner/io/utf8_text.h"

namespace phdslam::validation {
namespace {

std::string KnownKeys(const nlohmann::json& object) {
  std::string keys;
  for (const auto& [key, value] : object.items()) {
    if (!keys.empty()) keys += ", ";
    keys += key;
  }
  return keys.empty() ? std::string("none") : keys;
}

bool IsIntegral(const nlohmann::json& v) {
  if (v.is_number_integer()) return true;
  if (!v.is_number_float()) return false;
  const double d = v.get<double>();
  return std::isfinite(d) && d == std::floor(d);
}

// Returns the override value converted to the default's numeric representation, or throws.
nlohmann::json CheckedValue(const nlohmann::json& def, const nlohmann::json& value,
                            std::string_view owner, const std::string& path) {
  const auto fail = [&](const std::string& expected) {
    throw std::invalid_argument(std::string(owner) + ": parameter '" + path + "' expects " +
                                expected + ", got " + params::Shown(value));
  };
  if (def.is_number()) {
    if (!value.is_number()) fail("a number");
    if (def.is_number_integer()) {
      if (!IsIntegral(value)) fail("an integer");
      return def.is_number_unsigned() && value.get<double>() >= 0.0
                 ? nlohmann::json(value.get<std::uint64_t>())
                 : nlohmann::json(value.get<std::int64_t>());
    }
    return nlohmann::json(value.get<double>());
  }
  if (def.is_boolean() && !value.is_boolean()) fail("true or false");
  if (def.is_string() && !value.is_string()) fail("a string");
  if (def.is_array() && !value.is_array()) fail("an array");
  if (def.is_object() && !value.is_object()) fail("an object");
  return value;
}

void ApplyInto(nlohmann::json& target, const nlohmann::json& overrides, std::string_view owner,
               const std::string& prefix) {
  for (const auto& [key, value] : overrides.items()) {
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    if (!target.contains(key)) {
      throw std::invalid_argument(std::string(owner) + ": unknown parameter '" + path +
                                  "' (known: " + KnownKeys(target) + ")");
    }
    nlohmann::json& slot = target[key];
    if (slot.is_object() && value.is_object()) {
      ApplyInto(slot, value, owner, path);
    } else {
      slot = CheckedValue(slot, value, owner, path);
    }
  }
}

}  // namespace

nlohmann::json ApplyOverrides(const nlohmann::json& defaults, const nlohmann::json& overrides,
                              std::string_view owner) {
  if (!overrides.is_object()) {
    throw std::invalid_argument(std::string(owner) +
                                ": parameter overrides must be an object, got " +
                                params::Shown(overrides));
  }
  nlohmann::json resolved = defaults.is_null() ? nlohmann::json::object() : defaults;
  ApplyInto(resolved, overrides, owner, "");
  return resolved;
}

ParameterAssignment ParseParameterAssignment(std::string_view text, std::string_view option) {
  const std::string name(option);
  RequireUtf8(text, name);
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos) {
    throw std::invalid_argument(name + " '" + std::string(text) + "': expected key=value");
  }
  std::string_view key = text.substr(0, eq);
  const std::string value_text(text.substr(eq + 1));
  ParameterAssignment out;
  if (const std::size_t colon = key.find(':'); colon != std::string_view::npos) {
    out.estimator = std::string(key.substr(0, colon));
    key = key.substr(colon + 1);
    if (out.estimator.empty()) {
      throw std::invalid_argument(name + " '" + std::string(text) + "': empty estimator name");
    }
  }
  std::vector<std::string> segments;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    const std::string_view segment = key.substr(start, dot - start);
    if (segment.empty()) {
      throw std::invalid_argument(name + " '" + std::string(text) +
                                  "': empty key or key segment (expected [estimator:]key=value)");
    }
    segments.emplace_back(segment);
    if (dot == std::string_view::npos) break;
    start = dot + 1;
  }
  nlohmann::json value = nlohmann::json::parse(value_text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) value = value_text;
  for (auto it = segments.rbegin(); it != segments.rend(); ++it) {
    nlohmann::json wrapped = nlohmann::json::object();
    wrapped[*it] = std::move(value);
    value = std::move(wrapped);
  }
  out.overrides = std::move(value);
  return out;
}

void MergeJsonObjects(nlohmann::json& a, const nlohmann::json& b) {
  for (const auto& [key, value] : b.items()) {
    if (a.contains(key) && a[key].is_object() && value.is_object()) {
      MergeJsonObjects(a[key], value);
    } else {
      a[key] = value;
    }
  }
}

}  // namespace phdslam::validation
