// Detects a first argument that is neither an option nor a subcommand ("phdslam nosuch --help"),
// which CLI11 would answer with the main help and exit 0, so that a script probing for a
// subcommand would be told it exists.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace phdslam::apps {

/// The first argument when it is not an option (no leading '-') and names no subcommand of
/// `app`; "" otherwise.
inline std::string UnknownSubcommand(const CLI::App& app, int argc, char** argv) {
  if (argc < 2) return "";
  std::string first = argv[1];
  if (first.empty() || first.front() == '-') return "";
  for (const CLI::App* candidate : app.get_subcommands({})) {
    if (candidate->get_name() == first) return "";
  }
  return first;
}

}  // namespace phdslam::apps
