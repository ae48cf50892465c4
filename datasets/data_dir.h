// Where the shared data sets live.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace phdslam::datasets {

/// Name of the environment variable that overrides the compiled default data folder.
inline constexpr const char* kDataDirEnvVar = "PHDSLAM_DATA";

/// Resolves the data folder, in this order: `flag` (the --data-dir option) when given; else the
/// environment variable PHDSLAM_DATA when set and non-empty; else the compiled default
/// PHDSLAM_DEFAULT_DATA_DIR (../shared/datasets next to the repository).
/// Throws std::runtime_error naming the folder and where it came from when it is not an existing
/// directory.
std::filesystem::path ResolveDataDir(const std::optional<std::string>& flag);

}  // namespace phdslam::datasets
