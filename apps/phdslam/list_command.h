// `phdslam list`: the known scenarios with their options, and the known estimators with their
// parameters (default, accepted values, meaning) from the tables that parse `--set`;
// `--estimator NAME` shows one estimator.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace phdslam::apps {

struct ListArguments {
  std::string estimator;  ///< empty: every scenario and estimator
};

void AddListCommand(CLI::App& app, ListArguments& a);

/// Prints the list to standard output and returns 0; throws std::invalid_argument listing the
/// known names for an unknown --estimator.
int List(const ListArguments& a);

}  // namespace phdslam::apps
