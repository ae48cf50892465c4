// Where the data sets live: the data folder (--data-dir, PHDSLAM_DATA, the compiled default) and
// the repository's own folder of the data sets it carries (datasets/data).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace phdslam::datasets {

/// Name of the environment variable that overrides the compiled default data folder.
inline constexpr const char* kDataDirEnvVar = "PHDSLAM_DATA";

/// The data folder a run would read, and where that choice came from.
struct DataDirSetting {
  std::filesystem::path dir;
  std::string origin;  ///< e.g. "the --data-dir option"; for messages
};

/// The data folder in this order: `flag` (the --data-dir option) when given; else the environment
/// variable PHDSLAM_DATA when set and non-empty; else the compiled default
/// PHDSLAM_DEFAULT_DATA_DIR (../shared/datasets next to the repository). Does not check that it
/// exists: a data folder is needed only by the data sets that live only there.
DataDirSetting DataDirFromSettings(const std::optional<std::string>& flag);

/// DataDirFromSettings(flag).dir, checked: throws std::runtime_error naming the folder and where
/// it came from when it is not an existing directory (and how to get the data sets).
std::filesystem::path ResolveDataDir(const std::optional<std::string>& flag);

/// The repository's folder of the data sets it carries (PHDSLAM_BUNDLED_DATA_DIR, that is
/// datasets/data of the source tree), laid out as a data folder: today the paper's synthetic
/// scenario, phdslam3-synthetic/Environment_SLAM.mat.
std::filesystem::path BundledDataDir();

/// The folder to read `files` (paths relative to a data folder) from: the data folder of
/// DataDirFromSettings(flag) when it holds every one of them, else BundledDataDir() when it does.
/// Throws std::runtime_error naming the first missing file and both folders otherwise.
std::filesystem::path ResolveDataDirFor(const std::optional<std::string>& flag,
                                        const std::vector<std::filesystem::path>& files);

}  // namespace phdslam::datasets
