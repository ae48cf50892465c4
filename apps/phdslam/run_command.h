// `phdslam run`: Monte Carlo runs of one or more estimators on a scenario, given by options or
// by an experiment file (whose values the options given override: validation/runner/experiment/
// option_precedence.h).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "validation/runner/experiment/option_precedence.h"

namespace phdslam::apps {

struct RunArguments {
  std::string experiment_file;
  std::string scenario;
  std::string estimators;
  std::string particles = "1";
  std::string seeds;
  std::string out;
  std::string data_dir;
  int steps = 0;
  int jobs = 0;
  std::string experiment = "default";
  double detection_probability = 0.0;
  double clutter_rate = 0.0;
  std::vector<std::string> assignments;
  std::vector<std::string> scenario_assignments;
  std::string shard;
  bool particles_trace = false;
  bool map_ospa = false;
  double map_ospa_cutoff = 0.0;
  bool quiet = false;
  // Options whose presence matters (command-line values override an experiment file's).
  CLI::Option* experiment_file_option = nullptr;
  CLI::Option* scenario_option = nullptr;
  CLI::Option* estimator_option = nullptr;
  CLI::Option* particles_option = nullptr;
  CLI::Option* seeds_option = nullptr;
  CLI::Option* steps_option = nullptr;
  CLI::Option* jobs_option = nullptr;
  CLI::Option* experiment_name_option = nullptr;
  CLI::Option* data_dir_option = nullptr;
  CLI::Option* pd_option = nullptr;
  CLI::Option* clutter_option = nullptr;
  CLI::Option* map_ospa_cutoff_option = nullptr;
};

void AddRunCommand(CLI::App& app, RunArguments& a);

/// The options of `a` that were given on the command line.
validation::ExperimentOptions GivenOptions(const RunArguments& a);

/// Runs the experiment; returns the exit code (kExitRunFailed when a run failed,
/// kExitInterrupted on Ctrl-C).
int Run(const RunArguments& a);

}  // namespace phdslam::apps
