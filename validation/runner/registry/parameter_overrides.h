// Estimator parameter overrides: `--set key=value` strings and experiment-file values are merged
// into an estimator's default parameters, rejecting unknown keys and mismatched types so that a
// typo never silently runs the defaults.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace phdslam::validation {

/// Returns `defaults` with every key of `overrides` replaced. Nested objects are merged key by
/// key. Throws std::invalid_argument naming `owner` and the key when a key is not in `defaults`,
/// when a value's type differs from the default's (numbers are interchangeable, except that a
/// non-integral number cannot replace an integer), or when `overrides` is not an object.
nlohmann::json ApplyOverrides(const nlohmann::json& defaults, const nlohmann::json& overrides,
                              std::string_view owner);

/// One parsed `--set` argument.
struct ParameterAssignment {
  std::string estimator;     ///< empty: applies to every selected estimator
  nlohmann::json overrides;  ///< a one-key object, nested for dotted keys
};

/// Parses `[estimator:]key[.subkey...]=value`. The value is read as JSON when it parses (numbers,
/// true/false, null, quoted strings, arrays, objects) and is otherwise taken as a plain string.
/// Throws std::invalid_argument for text that is not UTF-8, a missing '=', an empty key or an
/// empty key segment; the messages name `option`, the command-line option the text came from.
ParameterAssignment ParseParameterAssignment(std::string_view text,
                                             std::string_view option = "--set");

/// Merges `b` into `a` key by key (objects recursively; other values of `b` win).
void MergeJsonObjects(nlohmann::json& a, const nlohmann::json& b);

}  // namespace phdslam::validation
