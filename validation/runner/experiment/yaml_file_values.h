// The values of a YAML file, read with errors that name the file and the line of the value:
// "<file>:<line>: <message>". Used by the experiment-file reader and by the rows of the
// experiment key table (experiment_keys.h) that read one key each.
#pragma once

#include <yaml-cpp/yaml.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <type_traits>
#include <utility>

namespace phdslam::validation {

/// Builds "<source>:<line>: <message>" errors for the nodes of one file.
class YamlFileErrors {
 public:
  explicit YamlFileErrors(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const YAML::Node& node, const std::string& message) const;
  [[noreturn]] void Fail(const std::string& message) const;
  [[nodiscard]] const std::string& source() const { return source_; }

 private:
  std::string source_;
};

/// Throws "<source>:<line>: unknown key '<k>' in <where> (known: ...)" when `map` has a key not
/// in `known` (and "<where>: expected a mapping ..." when it is not a mapping).
void RequireKnownKeys(const YAML::Node& map, const std::set<std::string>& known,
                      const std::string& where, const YamlFileErrors& errors);

/// A scalar's text, refused when it is not UTF-8: the file itself was checked, but the YAML reader
/// turns some byte sequences of valid text into bytes that are not (e.g. a lone 0x85, NEL).
const std::string& Utf8Scalar(const YAML::Node& node, const YamlFileErrors& errors);

/// The text of the single value under `key`; "'<key>': expected a single value" otherwise.
std::string ScalarText(const YAML::Node& node, const std::string& key,
                       const YamlFileErrors& errors);

/// The integer or number under `key`; "'<key>': '<text>' is not an integer" (or "a number").
template <typename T>
T YamlNumber(const YAML::Node& node, const std::string& key, const YamlFileErrors& errors) {
  const std::string text = ScalarText(node, key, errors);
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    errors.Fail(node, "'" + key + "': '" + text + "' is not " +
                          (std::is_integral_v<T> ? "an integer" : "a number"));
  }
}

/// A YAML value as JSON: mappings and sequences recursively; a quoted scalar is a string; a plain
/// scalar is read as JSON when it parses (numbers, true, false, null), as null when it is `~` or
/// empty, and as a string otherwise, like the values of `--set`.
nlohmann::json YamlToJson(const YAML::Node& node, const YamlFileErrors& errors);

/// One value of a file with the key it is under, as a row of the experiment key table reads it.
struct YamlKeyValue {
  const YAML::Node& node;
  const std::string& key;
  const YamlFileErrors& errors;

  /// Throws "<source>:<line>: '<key>': <message>".
  [[noreturn]] void Fail(const std::string& message) const {
    errors.Fail(node, "'" + key + "': " + message);
  }
  [[nodiscard]] std::string Text() const { return ScalarText(node, key, errors); }
  template <typename T>
  [[nodiscard]] T Number() const {
    return YamlNumber<T>(node, key, errors);
  }
};

}  // namespace phdslam::validation
