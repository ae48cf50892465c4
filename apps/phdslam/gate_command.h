// `phdslam gate`: the accuracy gates (ci/GATES.md) over any results folder, an ingested outside
// filter's included. The checker is ci/gates.py, the one CI runs, so both print the same table.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace phdslam::apps {

struct GateArguments {
  std::string gates;
  std::string results;
  std::string baseline;
  std::string tiers = "exact,paired,anchor";
  std::string csv;
};

void AddGateCommand(CLI::App& app, GateArguments& a);

/// Runs `python3 ci/gates.py check ...` and returns its exit code (0 pass, 1 a gate failed, 2 bad
/// input); the checker's path is compiled in, or given by the environment variable
/// PHDSLAM_GATES_SCRIPT.
int Gate(const GateArguments& a);

}  // namespace phdslam::apps
