// `phdslam export` and `phdslam ingest`: a scenario's filter inputs for an external filter, and
// that filter's outputs back into a results folder (validation/EXPORT_FORMAT.md).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace phdslam::apps {

// The scenario options of `export` and `ingest`, as `run` takes them.
struct ScenarioArguments {
  std::string scenario;
  std::string seeds;
  std::string data_dir;
  int steps = 0;
  double detection_probability = 0.0;
  double clutter_rate = 0.0;
  std::vector<std::string> scenario_assignments;
  CLI::Option* scenario_option = nullptr;
  CLI::Option* seeds_option = nullptr;
  CLI::Option* data_dir_option = nullptr;
  CLI::Option* steps_option = nullptr;
  CLI::Option* pd_option = nullptr;
  CLI::Option* clutter_option = nullptr;
};

struct ExportArguments {
  ScenarioArguments scenario;
  std::string out;
};

struct IngestArguments {
  ScenarioArguments scenario;
  std::string from;
  std::string estimator;
  std::string out;
  std::string export_dir;
  std::string description = "external estimator (phdslam ingest)";
  std::string experiment = "default";
  int particles = 1;
  bool replace = false;
};

void AddExportCommand(CLI::App& app, ExportArguments& a);
void AddIngestCommand(CLI::App& app, IngestArguments& a);
int Export(const ExportArguments& a);
int Ingest(const IngestArguments& a);

}  // namespace phdslam::apps
