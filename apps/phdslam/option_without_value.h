// Detects an option given without its value ("--seeds --out DIR"), which CLI11 would take as
// seeds = "--out" and then report the misleading "--out is required".
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace phdslam::apps {

/// The first option of the chosen subcommand that takes a value but is followed by another of its
/// options (or by nothing); "" when there is none.
inline std::string OptionWithoutValue(const CLI::App& app, int argc, char** argv) {
  const CLI::App* sub = nullptr;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (sub == nullptr) {
      for (const CLI::App* candidate : app.get_subcommands({})) {
        if (candidate->get_name() == arg) sub = candidate;
      }
      continue;
    }
    if (arg.rfind("--", 0) != 0 || arg.find('=') != std::string::npos) continue;
    const CLI::Option* option = sub->get_option_no_throw(arg);
    if (option == nullptr || option->get_expected_min() == 0) continue;  // unknown, or a flag
    if (i + 1 == argc) return arg;
    const std::string next = argv[i + 1];
    if (next.rfind("--", 0) == 0 && sub->get_option_no_throw(next) != nullptr) return arg;
    ++i;
  }
  return "";
}

}  // namespace phdslam::apps
