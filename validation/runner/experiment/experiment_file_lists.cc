#include "validation/runner/experiment/experiment_file_lists.h"

#include <cmath>
#include <set>
#include <stdexcept>

#include "src/core/parameter_table.h"
#include "validation/runner/io/list_arguments.h"

namespace phdslam::validation {
namespace {

std::vector<int> ParticleList(const YAML::Node& node, const std::string& key,
                              const YamlFileErrors& errors) {
  std::vector<int> particles;
  if (node.IsScalar()) {
    particles.push_back(YamlNumber<int>(node, key, errors));
  } else if (node.IsSequence() && node.size() > 0) {
    for (const auto& item : node) particles.push_back(YamlNumber<int>(item, key, errors));
  } else {
    errors.Fail(node, "'" + key + "': expected a particle count or a list such as [1, 10, 100]");
  }
  std::set<int> seen;
  for (int n : particles) {
    if (n < 1) errors.Fail(node, "'" + key + "': particle count " + std::to_string(n) + " is < 1");
    if (n > kMaxParticles) {
      errors.Fail(node, "'" + key + "': particle count " + std::to_string(n) + " is more than " +
                            std::to_string(kMaxParticles));
    }
    if (!seen.insert(n).second) {
      errors.Fail(node, "'" + key + "': particle count " + std::to_string(n) + " is listed twice");
    }
  }
  return particles;
}

ExperimentSweep ReadSweepDimension(const YAML::Node& node, const YamlFileErrors& errors) {
  RequireKnownKeys(node, {"parameter", "values"}, "'sweep'", errors);
  if (!node["parameter"] || !node["values"]) {
    errors.Fail(node, "'sweep' needs 'parameter' and 'values' (a list)");
  }
  ExperimentSweep sweep;
  sweep.parameter = ScalarText(node["parameter"], "parameter", errors);
  if (sweep.parameter.empty()) errors.Fail(node["parameter"], "'sweep.parameter' is empty");
  const YAML::Node values = node["values"];
  if (!values.IsSequence() || values.size() == 0) {
    errors.Fail(values, "'sweep.values' of '" + sweep.parameter + "': expected a non-empty list");
  }
  for (const auto& v : values) {
    const nlohmann::json value = YamlToJson(v, errors);
    if (!value.is_number() && !value.is_boolean() && !value.is_string()) {
      errors.Fail(v, "'sweep.values' of '" + sweep.parameter +
                         "': expected numbers, true/false or names, got " + params::Shown(value));
    }
    if (value.is_number() && !std::isfinite(value.get<double>())) {
      errors.Fail(v, "'sweep.values' of '" + sweep.parameter + "': a value is not finite");
    }
    for (const nlohmann::json& earlier : sweep.values) {
      if (earlier == value) {
        errors.Fail(v, "'sweep.values' of '" + sweep.parameter + "': " + params::Shown(value) +
                           " is listed twice");
      }
    }
    sweep.values.push_back(value);
  }
  return sweep;
}

std::vector<ExperimentSweep> SweepDimensions(const YAML::Node& node, const YamlFileErrors& errors) {
  if (node.IsMap()) return {ReadSweepDimension(node, errors)};
  if (!node.IsSequence() || node.size() == 0) {
    errors.Fail(node, "'sweep': expected {parameter: ..., values: [...]} or a list of them");
  }
  std::vector<ExperimentSweep> grid;
  for (const auto& item : node) {
    grid.push_back(ReadSweepDimension(item, errors));
    for (std::size_t i = 0; i + 1 < grid.size(); ++i) {
      if (grid[i].parameter == grid.back().parameter) {
        errors.Fail(item, "'sweep': parameter '" + grid.back().parameter + "' is listed twice");
      }
    }
  }
  return grid;
}

}  // namespace

std::vector<int> ParticleList(const YamlKeyValue& value) {
  return ParticleList(value.node, value.key, value.errors);
}

std::vector<std::uint64_t> SeedList(const YamlKeyValue& value) {
  const YAML::Node& node = value.node;
  std::string text;
  if (node.IsScalar()) {
    text = node.Scalar();
  } else if (node.IsSequence() && node.size() > 0) {
    for (const auto& item : node) {
      if (!text.empty()) text += ",";
      text += ScalarText(item, value.key, value.errors);
    }
  } else {
    value.Fail("expected a range such as 1-100, a seed, or a list of them");
  }
  try {
    return ParseSeedList(text);
  } catch (const std::invalid_argument& e) {
    value.errors.Fail(node, e.what());
  }
}

std::vector<ExperimentEstimator> EstimatorList(const YamlKeyValue& value) {
  const YAML::Node& node = value.node;
  const YamlFileErrors& errors = value.errors;
  if (!node.IsSequence() || node.size() == 0) {
    value.Fail("expected a list of names or {name: ..., set: {...}} items");
  }
  std::vector<ExperimentEstimator> estimators;
  std::set<std::string> names;
  for (const auto& item : node) {
    ExperimentEstimator e;
    if (item.IsScalar()) {
      e.name = Utf8Scalar(item, errors);
    } else if (item.IsMap()) {
      RequireKnownKeys(item, {"name", "set", "particles"}, "an 'estimators' item", errors);
      if (!item["name"]) errors.Fail(item, "an 'estimators' item has no 'name'");
      e.name = ScalarText(item["name"], "name", errors);
      if (const YAML::Node set = item["set"]) {
        if (!set.IsMap()) errors.Fail(set, "'set' of '" + e.name + "': expected a mapping");
        e.overrides = YamlToJson(set, errors);
      }
      if (const YAML::Node particles = item["particles"]) {
        e.particles = ParticleList(particles, "particles", errors);
      }
    } else {
      errors.Fail(item, "an 'estimators' item must be a name or a mapping with 'name'");
    }
    if (e.name.empty()) errors.Fail(item, "an estimator name is empty");
    if (!names.insert(e.name).second) {
      errors.Fail(item, "estimator '" + e.name + "' is listed twice");
    }
    estimators.push_back(std::move(e));
  }
  return estimators;
}

void ReadScenarioOptions(const YamlKeyValue& value, Experiment& x) {
  if (!value.node.IsMap()) value.Fail("expected a mapping of keys to values");
  for (const auto& item : value.node) {
    try {
      SetScenarioOption(x, Utf8Scalar(item.first, value.errors),
                        YamlToJson(item.second, value.errors));
    } catch (const std::invalid_argument& e) {
      value.errors.Fail(item.second, "'" + value.key + "': " + e.what());
    }
  }
}

std::vector<ExperimentSweep> ReadSweep(const YamlKeyValue& value, const Experiment& x) {
  std::vector<ExperimentSweep> sweep = SweepDimensions(value.node, value.errors);
  for (const ExperimentSweep& d : sweep) {
    if (SetsScenarioOption(x, d.parameter)) {
      value.errors.Fail(value.node,
                        "'" + d.parameter + "' is swept; remove it from 'scenario_options'");
    }
  }
  return sweep;
}

}  // namespace phdslam::validation
