#include "validation/runner/experiment/yaml_file_values.h"

#include <stdexcept>

#include "validation/runner/io/utf8_text.h"

namespace phdslam::validation {

void YamlFileErrors::Fail(const YAML::Node& node, const std::string& message) const {
  const YAML::Mark mark = node.Mark();
  throw std::invalid_argument(
      source_ + (mark.is_null() ? "" : ":" + std::to_string(mark.line + 1)) + ": " + message);
}

void YamlFileErrors::Fail(const std::string& message) const {
  throw std::invalid_argument(source_ + ": " + message);
}

void RequireKnownKeys(const YAML::Node& map, const std::set<std::string>& known,
                      const std::string& where, const YamlFileErrors& errors) {
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

const std::string& Utf8Scalar(const YAML::Node& node, const YamlFileErrors& errors) {
  const std::string& text = node.Scalar();
  if (const auto bad = FirstInvalidUtf8Byte(text)) {
    errors.Fail(node, "a value the YAML reader decoded is not valid UTF-8 (byte " +
                          ByteText(text[*bad]) + ")");
  }
  return text;
}

std::string ScalarText(const YAML::Node& node, const std::string& key,
                       const YamlFileErrors& errors) {
  if (!node.IsScalar()) errors.Fail(node, "'" + key + "': expected a single value");
  return Utf8Scalar(node, errors);
}

nlohmann::json YamlToJson(const YAML::Node& node, const YamlFileErrors& errors) {
  switch (node.Type()) {
    case YAML::NodeType::Null:
      return nullptr;
    case YAML::NodeType::Sequence: {
      nlohmann::json array = nlohmann::json::array();
      for (const auto& item : node) array.push_back(YamlToJson(item, errors));
      return array;
    }
    case YAML::NodeType::Map: {
      nlohmann::json object = nlohmann::json::object();
      for (const auto& item : node) {
        object[Utf8Scalar(item.first, errors)] = YamlToJson(item.second, errors);
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

}  // namespace phdslam::validation
