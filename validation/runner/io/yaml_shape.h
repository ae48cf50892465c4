// A check of an experiment file's YAML before it is turned into nodes: no aliases (a few hundred
// bytes of nested aliases expand to gigabytes), no key twice in one mapping (the reader would use
// one value and config.json record another), and a bounded nesting depth and size.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace phdslam::validation {

inline constexpr std::size_t kMaxYamlDepth = 64;
inline constexpr std::size_t kMaxYamlNodes = 100000;

/// Throws std::invalid_argument "<source>:<line>: ..." on an alias, a repeated mapping key, more
/// than kMaxYamlDepth nested collections or more than kMaxYamlNodes nodes, and
/// "<source>: line L, column C: YAML syntax error: ..." on a syntax error.
void CheckYamlShape(std::string_view text, const std::string& source);

}  // namespace phdslam::validation
