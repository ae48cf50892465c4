// `phdslam ingest`: an external filter's per-seed outputs (trajectory, final map, optional pose
// covariances, per-step maps, associations and timing) turned into run folders of a results
// folder, written by the runner's own writers, so that summary.csv, runs.csv, `merge`, `compare`,
// the gates and the report treat the external filter like any registered estimator. The input
// layout is documented in validation/EXPORT_FORMAT.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "validation/runner/evaluation/run_metrics.h"
#include "validation/runner/evaluation/run_record.h"
#include "validation/runner/interchange/external_run_reader.h"
#include "validation/runner/registry/scenario_registry.h"

namespace phdslam::validation {

/// Folder inside the results folder where ingest writes its runs before moving them into place.
inline constexpr const char* kIngestStagingFolder = ".ingest-staging";

struct IngestRequest {
  std::filesystem::path from;  ///< holds seed-<s>/ per seed
  std::string estimator;       ///< the name its runs are filed under
  std::string description = "external estimator (phdslam ingest)";
  int particles = 1;                   ///< the group's particle count label
  std::string experiment = "default";  ///< must match the results folder's experiment
  ScenarioSource scenario;
  std::vector<std::uint64_t> seeds;
  /// When set: the export folder the filter read; every seed's regenerated input files must
  /// match its SHA256SUMS (the scores are computed on the scenario the filter saw).
  std::optional<std::filesystem::path> export_dir;
  MetricSettings metrics;
  /// Replace the runs the estimator already has in the results folder (otherwise refused).
  bool replace = false;
};

struct IngestReport {
  std::size_t runs = 0;
  std::vector<std::filesystem::path> replaced;  ///< run folders of the estimator found before
  double wall_seconds = 0.0;
};

/// Verifies the export's files on disk against its SHA256SUMS (with `export_dir`), reads and
/// evaluates every seed (nothing is written when one fails), writes the run folders into
/// <out>/.ingest-staging and moves them into place when all are written, then writes the truth
/// files, config.json (joined with the folder's own, refused like `run` refuses other
/// settings), summary.csv, runs.csv and timing.json. Throws std::invalid_argument for a bad
/// request, a folder made with other settings, or an estimator that already has runs in `out`
/// without request.replace (with it, those runs are removed: IngestReport::replaced);
/// std::runtime_error for unreadable, edited or inconsistent inputs.
IngestReport IngestResults(const IngestRequest& request, const std::filesystem::path& out);

}  // namespace phdslam::validation
