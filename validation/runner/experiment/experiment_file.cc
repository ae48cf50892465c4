#include "validation/runner/experiment/experiment_file.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>
#include <stdexcept>

#include "src/core/parameter_table.h"
#include "validation/runner/io/list_arguments.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/utf8_text.h"
#include "validation/runner/io/yaml_shape.h"

namespace phdslam::validation {
namespace {

// Builds "<source>:<line>: <message>" errors for the nodes of one file.
class FileErrors {
 public:
  explicit FileErrors(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const YAML::Node& node, const std::string& message) const {
    const YAML::Mark mark = node.Mark();
    throw std::invalid_argument(
        source_ + (mark.is_null() ? "" : ":" + std::to_string(mark.line + 1)) + ": " + message);
  }
  [[noreturn]] void Fail(const std::string& message) const {
    throw std::invalid_argument(source_ + ": " + message);
  }
  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

// Checks that `map` is a mapping whose keys are all in `known`.
void RequireKnownKeys(const YAML::Node& map, const std::set<std::string>& known,
                      const std::string& where, const FileErrors& errors) {
  if (!map.IsMap()) errors.Fail(map, where + ": expected a mapping of keys to values");
  for (const auto& item : map) {
    const std::string key = item.first.Scalar();
    if (!known.contains(key)) {
      std::string list;
      for (const std::string& k : known) {
        if (!list.empty()) list += ", ";
        list += k;
      }
      errors.Fail(item.first, "unknown key '" + key + "' in " + where + " (known: " + list + ")");
    }
  }
}

// A scalar's text, refused when it is not UTF-8: the file itself was checked, but the YAML reader
// turns some byte sequences of valid text into bytes that are not (e.g. a lone 0x85, NEL).
const std::string& Utf8Scalar(const YAML::Node& node, const FileErrors& errors) {
  const std::string& text = node.Scalar();
  if (const auto bad = FirstInvalidUtf8Byte(text)) {
    errors.Fail(node, "a value the YAML reader decoded is not valid UTF-8 (byte " +
                          ByteText(text[*bad]) + ")");
  }
  return text;
}

std::string ScalarText(const YAML::Node& node, const std::string& key, const FileErrors& errors) {
  if (!node.IsScalar()) errors.Fail(node, "'" + key + "': expected a single value");
  return Utf8Scalar(node, errors);
}

template <typename T>
T Number(const YAML::Node& node, const std::string& key, const FileErrors& errors) {
  const std::string text = ScalarText(node, key, errors);
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    errors.Fail(node, "'" + key + "': '" + text + "' is not " +
                          (std::is_integral_v<T> ? "an integer" : "a number"));
  }
}

// A YAML value as JSON: mappings and sequences recursively; a quoted scalar is a string; a plain
// scalar is read as JSON when it parses (numbers, true, false, null), as null when it is `~` or
// empty, and as a string otherwise, like the values of `--set`.
nlohmann::json ToJson(const YAML::Node& node, const FileErrors& errors) {
  switch (node.Type()) {
    case YAML::NodeType::Null:
      return nullptr;
    case YAML::NodeType::Sequence: {
      nlohmann::json array = nlohmann::json::array();
      for (const auto& item : node) array.push_back(ToJson(item, errors));
      return array;
    }
    case YAML::NodeType::Map: {
      nlohmann::json object = nlohmann::json::object();
      for (const auto& item : node) {
        object[Utf8Scalar(item.first, errors)] = ToJson(item.second, errors);
      }
      return object;
    }
    case YAML::NodeType::Scalar: {
      const std::string& text = Utf8Scalar(node, errors);
      if (node.Tag() == "!") return text;  // quoted
      if (text == "~" || text.empty()) return nullptr;
      nlohmann::json parsed = nlohmann::json::parse(text, nullptr, false);
      if (!parsed.is_discarded() && !parsed.is_string()) return parsed;
      return text;
    }
    case YAML::NodeType::Undefined:
      break;
  }
  errors.Fail(node, "undefined value");
}

std::vector<int> ParticleList(const YAML::Node& node, const std::string& key,
                              const FileErrors& errors) {
  std::vector<int> particles;
  if (node.IsScalar()) {
    particles.push_back(Number<int>(node, key, errors));
  } else if (node.IsSequence() && node.size() > 0) {
    for (const auto& item : node) particles.push_back(Number<int>(item, key, errors));
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

std::vector<std::uint64_t> SeedList(const YAML::Node& node, const FileErrors& errors) {
  // A range "1-100", a seed, or a list of seeds and ranges: the same grammar as --seeds.
  std::string text;
  if (node.IsScalar()) {
    text = node.Scalar();
  } else if (node.IsSequence() && node.size() > 0) {
    for (const auto& item : node) {
      if (!text.empty()) text += ",";
      text += ScalarText(item, "seeds", errors);
    }
  } else {
    errors.Fail(node, "'seeds': expected a range such as 1-100, a seed, or a list of them");
  }
  try {
    return ParseSeedList(text);
  } catch (const std::invalid_argument& e) {
    errors.Fail(node, e.what());
  }
}

std::vector<ExperimentEstimator> EstimatorList(const YAML::Node& node, const FileErrors& errors) {
  if (!node.IsSequence() || node.size() == 0) {
    errors.Fail(node, "'estimators': expected a list of names or {name: ..., set: {...}} items");
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
        e.overrides = ToJson(set, errors);
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

void ReadScenarioOptions(const YAML::Node& node, const FileErrors& errors, Experiment& x) {
  if (!node.IsMap()) errors.Fail(node, "'scenario_options': expected a mapping of keys to values");
  for (const auto& item : node) {
    try {
      SetScenarioOption(x, Utf8Scalar(item.first, errors), ToJson(item.second, errors));
    } catch (const std::invalid_argument& e) {
      errors.Fail(item.second, std::string("'scenario_options': ") + e.what());
    }
  }
}

ExperimentSweep ReadSweepDimension(const YAML::Node& node, const FileErrors& errors) {
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
    const nlohmann::json value = ToJson(v, errors);
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

// `sweep: {parameter: ..., values: [...]}` or a grid `sweep: [{...}, {...}]`.
std::vector<ExperimentSweep> ReadSweep(const YAML::Node& node, const FileErrors& errors) {
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

Experiment ParseExperimentYaml(std::string_view text, const std::string& source,
                               const std::string& default_name) {
  const FileErrors errors(source);
  RequireUtf8(text, source);
  CheckYamlShape(text, source);
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::ParserException& e) {
    errors.Fail("line " + std::to_string(e.mark.line + 1) + ", column " +
                std::to_string(e.mark.column + 1) + ": YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) errors.Fail("expected a mapping of keys (scenario, estimators, seeds, ...)");
  RequireKnownKeys(root,
                   {"name", "scenario", "estimators", "particles", "seeds", "steps",
                    "scenario_options", "jobs", "sweep", "map_ospa", "map_ospa_cutoff"},
                   "the experiment", errors);
  for (const char* key : {"scenario", "estimators", "seeds"}) {
    if (!root[key]) errors.Fail("the key '" + std::string(key) + "' is required");
  }
  Experiment x;
  x.name = root["name"] ? ScalarText(root["name"], "name", errors) : default_name;
  if (x.name.empty()) errors.Fail(root["name"], "'name' is empty");
  x.scenario = ScalarText(root["scenario"], "scenario", errors);
  x.estimators = EstimatorList(root["estimators"], errors);
  if (const YAML::Node particles = root["particles"]) {
    x.particles = ParticleList(particles, "particles", errors);
  }
  x.seeds = SeedList(root["seeds"], errors);
  if (const YAML::Node steps = root["steps"]) {
    x.steps = Number<int>(steps, "steps", errors);
    if (x.steps < 0) errors.Fail(steps, "'steps': expected >= 0 (0 = all)");
  }
  if (const YAML::Node options = root["scenario_options"]) ReadScenarioOptions(options, errors, x);
  if (const YAML::Node jobs = root["jobs"]) {
    x.jobs = Number<int>(jobs, "jobs", errors);
    if (*x.jobs < 0) errors.Fail(jobs, "'jobs': expected >= 0 (0 = one per hardware thread)");
  }
  if (const YAML::Node map_ospa = root["map_ospa"]) {
    const std::string flag = ScalarText(map_ospa, "map_ospa", errors);
    if (flag != "true" && flag != "false") {
      errors.Fail(map_ospa, "'map_ospa': expected true or false, got '" + flag + "'");
    }
    x.map_ospa = flag == "true";
  }
  if (const YAML::Node cutoff = root["map_ospa_cutoff"]) {
    x.map_ospa_cutoff = Number<double>(cutoff, "map_ospa_cutoff", errors);
    if (!(*x.map_ospa_cutoff > 0.0) || !std::isfinite(*x.map_ospa_cutoff)) {
      errors.Fail(cutoff, "'map_ospa_cutoff': expected a finite number > 0 (m)");
    }
  }
  if (const YAML::Node sweep = root["sweep"]) {
    x.sweep = ReadSweep(sweep, errors);
    for (const ExperimentSweep& d : x.sweep) {
      const bool pd_clash = d.parameter == kSweepParameterPd && x.pd;
      const bool clutter_clash = d.parameter == kSweepParameterClutterRate && x.clutter_rate;
      if (pd_clash || clutter_clash || x.scenario_settings.contains(d.parameter)) {
        errors.Fail(sweep, "'" + d.parameter + "' is swept; remove it from 'scenario_options'");
      }
    }
  }
  x.source = {{"path", source}, {"text", std::string(text)}, {"values", ToJson(root, errors)}};
  return x;
}

void SetScenarioOption(Experiment& experiment, const std::string& key,
                       const nlohmann::json& value) {
  if (key.empty()) throw std::invalid_argument("a scenario option key is empty");
  const bool pd = key == kSweepParameterPd;
  if (pd || key == kSweepParameterClutterRate) {
    if (!value.is_number() || !std::isfinite(value.get<double>())) {
      throw std::invalid_argument("scenario option '" + key + "': expected a number, got " +
                                  params::Shown(value));
    }
    (pd ? experiment.pd : experiment.clutter_rate) = value.get<double>();
    return;
  }
  experiment.scenario_settings[key] = value;
}

Experiment ReadExperimentFile(const std::filesystem::path& path) {
  return ParseExperimentYaml(ReadTextFile(path), path.string(), path.stem().string());
}

}  // namespace phdslam::validation
