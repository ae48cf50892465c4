// `phdslam run`: Monte Carlo runs of one or more estimators on a scenario, given by options or
// by an experiment file (whose values the options given override: validation/runner/experiment/
// option_precedence.h).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "apps/phdslam/experiment_options.h"
#include "validation/runner/experiment/option_precedence.h"

namespace phdslam::apps {

struct RunArguments {
  std::string experiment_file;
  std::string out;
  std::string shard;
  bool particles_trace = false;
  bool quiet = false;
  CLI::Option* experiment_file_option = nullptr;
  ExperimentOptionSet experiment;  ///< every option of the experiment key table
};

void AddRunCommand(CLI::App& app, RunArguments& a);

/// The options of `a` that were given on the command line.
validation::ExperimentOptions GivenOptions(const RunArguments& a);

/// Runs the experiment; returns the exit code (kExitRunFailed when a run failed,
/// kExitInterrupted on Ctrl-C).
int Run(const RunArguments& a);

}  // namespace phdslam::apps
