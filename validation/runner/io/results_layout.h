// Names of the files and folders of a results folder (see validation/README.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace phdslam::validation {

inline constexpr const char* kRunsFolder = "runs";
inline constexpr const char* kStepsFile = "steps.csv";
inline constexpr const char* kTrajectoryFile = "trajectory.tum";
inline constexpr const char* kMapFile = "map.csv";
inline constexpr const char* kParticlesFile = "particles.csv";  ///< only with --particles-trace
inline constexpr const char* kMetricsFile = "metrics.json";  ///< written last: marks a finished run
inline constexpr const char* kErrorFile = "error.json";      ///< a failed run's error
inline constexpr const char* kSummaryFile = "summary.csv";
inline constexpr const char* kRunsTableFile = "runs.csv";
inline constexpr const char* kConfigFile = "config.json";
inline constexpr const char* kTimingFile = "timing.json";
inline constexpr const char* kTruthMapFile = "truth_map.csv";
inline constexpr const char* kTruthFolder = "truth";
inline constexpr const char* kTruthTrajectoryFile = "truth.tum";
inline constexpr const char* kTruthGpsFile = "gps.csv";
inline constexpr const char* kSweepTableFile = "sweep.csv";  ///< at the root of a sweep
inline constexpr const char* kSweepFile = "sweep.json";      ///< at the root of a sweep
inline constexpr const char* kComparisonFile = "comparison.csv";

/// <estimator>-N<particles>
inline std::string GroupFolderName(const std::string& estimator, int particles) {
  return estimator + "-N" + std::to_string(particles);
}

/// seed-<seed>
inline std::string SeedFolderName(std::uint64_t seed) { return "seed-" + std::to_string(seed); }

/// <out>/runs/<estimator>-N<particles>/seed-<seed>
inline std::filesystem::path RunFolder(const std::filesystem::path& out,
                                       const std::string& estimator, int particles,
                                       std::uint64_t seed) {
  return out / kRunsFolder / GroupFolderName(estimator, particles) / SeedFolderName(seed);
}

/// <out>/truth/seed-<seed>
inline std::filesystem::path TruthFolder(const std::filesystem::path& out, std::uint64_t seed) {
  return out / kTruthFolder / SeedFolderName(seed);
}

}  // namespace phdslam::validation
