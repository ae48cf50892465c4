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
#include "validation/runner/registry/scenario_registry.h"

namespace phdslam::validation {

/// Files of one seed's external output folder, <from>/seed-<s>/.
inline constexpr const char* kExternalTrajectoryFile = "trajectory.tum";    ///< required
inline constexpr const char* kExternalMapFile = "map.csv";                  ///< required
inline constexpr const char* kExternalPoseCovFile = "pose_cov.csv";         ///< optional
inline constexpr const char* kExternalMapsFile = "maps.csv";                ///< optional
inline constexpr const char* kExternalAssociationFile = "association.csv";  ///< optional
inline constexpr const char* kExternalTimingFile = "timing.csv";            ///< optional
/// Optional, at <from>/: the external filter's parameters (a JSON object), stored as the run's
/// resolved parameters.
inline constexpr const char* kExternalParametersFile = "parameters.json";

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
};

struct IngestReport {
  std::size_t runs = 0;
  double wall_seconds = 0.0;
};

/// The RunRecord of one seed's external outputs in `folder` against `scenario`. Throws
/// std::runtime_error naming the file (and line) for a missing or unreadable file, a value that
/// is not a finite number, a trajectory whose pose count or time stamps differ from the
/// scenario's steps, a step index out of range or repeated, and a measurement index out of range.
RunRecord ReadExternalRun(const std::filesystem::path& folder, const datasets::Scenario& scenario,
                          const std::string& estimator, int particles);

/// Reads and evaluates every seed first (nothing is written when one fails), then writes the run
/// folders, truth files, config.json (joined with the folder's own, refused like `run` refuses
/// other settings), summary.csv, runs.csv and timing.json into `out`. Throws
/// std::invalid_argument for a bad request or a folder made with other settings,
/// std::runtime_error for unreadable or inconsistent inputs.
IngestReport IngestResults(const IngestRequest& request, const std::filesystem::path& out);

}  // namespace phdslam::validation
