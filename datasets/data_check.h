// Verifies the files of a data set in a data folder against the catalogue (data_catalog.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "datasets/data_catalog.h"

namespace phdslam::datasets {

enum class FileState { kVerified, kMissing, kCorrupt };

/// "verified", "missing" or "corrupt".
std::string FileStateName(FileState state);

struct FileCheck {
  std::filesystem::path path;  ///< the file looked at
  FileState state = FileState::kMissing;
  std::string detail;  ///< for a corrupt file: which size or SHA-256 differs
};

/// Checks the file at `path` against `expected`: missing when it is not a regular file, corrupt
/// when its size or its SHA-256 differs (the detail gives both values), else verified.
FileCheck VerifyDataFile(const std::filesystem::path& path, const DataFile& expected);

/// A data set as found: "present" (every file verified), "corrupt" (a file differs) or
/// "missing" (a file is absent, none differs).
struct DataSetCheck {
  std::string name;
  std::filesystem::path dir;     ///< the folder whose files were checked
  bool from_repository = false;  ///< dir is the repository's copy (BundledDataDir())
  std::vector<FileCheck> files;  ///< in catalogue order
  std::string State() const;
};

/// Checks every file of `entry` under `data_dir`. A data set the repository carries whose files
/// are all absent from `data_dir` is checked in BundledDataDir() instead, as the scenarios read it.
DataSetCheck CheckDataSet(const std::filesystem::path& data_dir, const DataSetEntry& entry);

}  // namespace phdslam::datasets
