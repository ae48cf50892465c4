#include "validation/runner/registry/estimator_parameter_list.h"

namespace phdslam::validation {
namespace {

nlohmann::json DefaultParameters(const EstimatorEntry& entry) {
  if (!entry.resolved_parameters || entry.parameters.empty()) return nlohmann::json::object();
  EstimatorRequest request;
  request.name = entry.name;
  request.particles = 1;
  return entry.resolved_parameters(request);
}

std::string ParameterLine(const EstimatorParameter& p, const std::string& indent) {
  const std::string use =
      p.used_only_with.empty() ? "" : " [used only with " + p.used_only_with + "]";
  return indent + p.key + " = " + p.default_value.dump() + " (" + p.accepted + "): " + p.meaning +
         use + "\n";
}

}  // namespace

std::vector<EstimatorParameter> EstimatorParameters(const EstimatorEntry& entry) {
  const nlohmann::json defaults = DefaultParameters(entry);
  std::vector<EstimatorParameter> out;
  out.reserve(entry.parameters.size());
  for (const params::FieldDescription& row : entry.parameters) {
    const auto it = defaults.find(row.key);
    out.push_back({row.key, it == defaults.end() ? nlohmann::json(nullptr) : *it, row.accepted,
                   row.meaning, row.used_only_with});
  }
  return out;
}

std::string FormatEstimatorParameters(const EstimatorEntry& entry, const std::string& indent) {
  const std::vector<EstimatorParameter> parameters = EstimatorParameters(entry);
  if (parameters.empty()) return indent + "(no parameters)\n";
  std::string text;
  for (const EstimatorParameter& p : parameters) text += ParameterLine(p, indent);
  return text;
}

}  // namespace phdslam::validation
