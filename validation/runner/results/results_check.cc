#include "validation/runner/results/results_check.h"

#include <cstdint>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/results/results_config.h"
#include "validation/runner/results/summary.h"

namespace phdslam::validation {
namespace {

namespace fs = std::filesystem;

// steps.csv of a finished run: complete lines, one row per step of metrics.json.
void CheckStepsFile(const fs::path& run) {
  const fs::path steps_path = run / kStepsFile;
  if (!fs::exists(steps_path)) return;
  const CsvTable table = ReadCsvFile(steps_path);
  const nlohmann::json metrics = ReadJsonObject(run / kMetricsFile);
  const auto steps = metrics.find("steps");
  if (steps == metrics.end() || !steps->is_number_unsigned()) return;
  const auto expected = steps->get<std::uint64_t>();
  if (table.rows.size() != expected) {
    throw std::runtime_error(steps_path.string() + ": " + std::to_string(table.rows.size()) +
                             " rows, but " + (run / kMetricsFile).string() + " counts " +
                             std::to_string(expected) + " steps (a file cut short?)");
  }
}

}  // namespace

void CheckResultsFolder(const fs::path& folder) {
  (void)ReadResults(folder);  // every metrics.json and error.json, as the summary reads them
  const fs::path runs = folder / kRunsFolder;
  if (!fs::is_directory(runs)) return;
  for (const auto& group : fs::directory_iterator(runs)) {
    if (!group.is_directory()) continue;
    for (const auto& run : fs::directory_iterator(group.path())) {
      if (run.is_directory() && fs::exists(run.path() / kMetricsFile)) CheckStepsFile(run.path());
    }
  }
}

}  // namespace phdslam::validation
