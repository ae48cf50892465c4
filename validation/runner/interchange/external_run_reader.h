// The readers of an external filter's per-seed outputs (the files `phdslam ingest` reads,
// validation/EXPORT_FORMAT.md): trajectory, final map, optional pose covariances, per-step maps,
// associations and timing, checked value by value and turned into a RunRecord.
#pragma once

#include <filesystem>
#include <string>

#include "datasets/scenario.h"
#include "validation/runner/evaluation/run_record.h"

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

/// Largest magnitude of any value ingest reads (coordinates in m, covariance entries, ms).
inline constexpr double kMaxIngestedValue = 1e9;

/// The RunRecord of one seed's external outputs in `folder` against `scenario`. Throws
/// std::runtime_error naming the file (and line) for a missing or unreadable file, a value that
/// is not a finite number or beyond +-kMaxIngestedValue, a negative variance, a covariance that
/// is not positive semi-definite, a map weight outside [0, 1], a negative time, a trajectory
/// whose pose count or time stamps differ from the scenario's steps, a step index out of range
/// or repeated, and a measurement index out of range.
RunRecord ReadExternalRun(const std::filesystem::path& folder, const datasets::Scenario& scenario,
                          const std::string& estimator, int particles);

}  // namespace phdslam::validation
