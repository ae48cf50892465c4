// A check of an experiment file's YAML before it is turned into nodes: no aliases (a few hundred
// bytes of nested aliases expand to gigabytes), no key twice in one mapping (the reader would use
// one value and config.json record another), and a bounded nesting depth and size.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace phdslam::validation {

inline constexpr std::size_t kMaxYamlDepth = 64;
inline constexpr std::size_t kMaxYamlNodes = 100000;
/// The largest experiment file read (1 MiB; the largest in validation/experiments is a few KiB).
inline constexpr std::uintmax_t kMaxExperimentFileBytes = std::uintmax_t{1} << 20;

/// Throws std::invalid_argument "<source>:<line>: ..." on an alias, a repeated mapping key, more
/// than kMaxYamlDepth nested collections, more than kMaxYamlNodes nodes or a second document, and
/// "<source>: line L, column C: YAML syntax error: ..." on a syntax error.
void CheckYamlShape(std::string_view text, const std::string& source);

}  // namespace phdslam::validation
