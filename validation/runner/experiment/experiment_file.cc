#include "validation/runner/experiment/experiment_file.h"

#include <yaml-cpp/yaml.h>

#include <set>
#include <stdexcept>

#include "validation/runner/experiment/experiment_keys.h"
#include "validation/runner/experiment/yaml_file_values.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/io/utf8_text.h"
#include "validation/runner/io/yaml_shape.h"

namespace phdslam::validation {
namespace {

YAML::Node LoadRoot(std::string_view text, const YamlFileErrors& errors) {
  RequireUtf8(text, errors.source());
  CheckYamlShape(text, errors.source());
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::ParserException& e) {
    errors.Fail("line " + std::to_string(e.mark.line + 1) + ", column " +
                std::to_string(e.mark.column + 1) + ": YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) errors.Fail("expected a mapping of keys (scenario, estimators, seeds, ...)");
  return root;
}

// The keys experiment files may have, and those they must have (in the table's order).
std::set<std::string> FileKeys() {
  std::set<std::string> keys;
  for (const ExperimentKey& key : ExperimentKeys()) {
    if (!key.file_key.empty()) keys.insert(key.file_key);
  }
  return keys;
}

void RequireKeys(const YAML::Node& root, const YamlFileErrors& errors) {
  RequireKnownKeys(root, FileKeys(), "the experiment", errors);
  for (const ExperimentKey& key : ExperimentKeys()) {
    if (key.required && !root[key.file_key]) {
      errors.Fail("the key '" + key.file_key + "' is required");
    }
  }
}

}  // namespace

Experiment ParseExperimentYaml(std::string_view text, const std::string& source,
                               const std::string& default_name) {
  const YamlFileErrors errors(source);
  const YAML::Node root = LoadRoot(text, errors);
  RequireKeys(root, errors);
  Experiment x;
  x.name = default_name;
  for (const ExperimentKey& key : ExperimentKeys()) {
    if (key.file_key.empty()) continue;
    if (const YAML::Node node = root[key.file_key]) {
      key.read_file(YamlKeyValue{node, key.file_key, errors}, x);
    }
  }
  if (x.name.empty()) errors.Fail("'name' is empty");
  x.source = {{"path", source}, {"text", std::string(text)}, {"values", YamlToJson(root, errors)}};
  return x;
}

Experiment ReadExperimentFile(const std::filesystem::path& path) {
  return ParseExperimentYaml(ReadTextFile(path, kMaxExperimentFileBytes), path.string(),
                             path.stem().string());
}

}  // namespace phdslam::validation
