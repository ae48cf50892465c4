// `phdslam data fetch NAME...` and `phdslam data check`: download the data sets into the data
// folder, verified against the SHA-256 list kept in the repository (datasets/data_catalog.cc), and
// list what the data folder holds (docs/guide/data-and-credits.md).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace phdslam::apps {

struct DataArguments {
  std::vector<std::string> names;  ///< fetch: data sets, or "all"
  std::string from;                ///< fetch: a mirror (folder, file:// or http(s) address)
  std::string data_dir;            ///< both: the data folder (default $PHDSLAM_DATA, then compiled)
};

void AddDataCommand(CLI::App& app, DataArguments& a);

/// Runs the `data` subcommand that was parsed; returns the exit code (1 when a data set is
/// corrupt or a fetch failed).
int Data(const CLI::App& app, const DataArguments& a);

}  // namespace phdslam::apps
