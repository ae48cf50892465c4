// `phdslam export` and `phdslam ingest`: a scenario's filter inputs for an external filter, and
// that filter's outputs back into a results folder (validation/EXPORT_FORMAT.md).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "apps/phdslam/experiment_options.h"

namespace phdslam::apps {

struct ExportArguments {
  ExperimentOptionSet scenario;  ///< the scenario options, as `run` takes them
  std::string out;
};

struct IngestArguments {
  ExperimentOptionSet scenario;  ///< the scenario options, as `run` takes them
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
