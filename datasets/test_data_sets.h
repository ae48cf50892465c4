// Test helper: the data sets a test reads. The synthetic scenario is always there (the data
// folder's copy, else the repository's); a test of Victoria Park or MRCLAM data skips, naming the
// data set and the folder, when the data folder does not hold it, and fails instead when
// CI=true or PHDSLAM_REQUIRE_DATA=1 (docs/guide/testing.md, "Data sets").
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "datasets/data_catalog.h"
#include "datasets/data_dir.h"
#include "datasets/paper_synthetic.h"

namespace phdslam::datasets::testing {

/// The folder the paper's synthetic scenario is read from (ResolveDataDirFor).
inline std::filesystem::path SyntheticDataDir() {
  return ResolveDataDirFor(std::nullopt, PaperSyntheticDataFiles());
}

/// Whether a missing data set fails a test: CI=true or PHDSLAM_REQUIRE_DATA=1.
inline bool DataSetsRequired() {
  const char* ci = std::getenv("CI");
  const char* require = std::getenv("PHDSLAM_REQUIRE_DATA");
  return (ci != nullptr && std::string(ci) == "true") ||
         (require != nullptr && std::string(require) == "1");
}

/// Where a data set was found, or why not.
struct DataSetLookup {
  std::optional<std::filesystem::path> dir;  ///< the data folder holding every file
  std::string reason;                        ///< when absent: data set, folder, missing file
};

/// The data folder (DataDirFromSettings) when it holds every file of data set `name` of the
/// catalogue (only presence is checked here; `phdslam data check` verifies the contents).
inline DataSetLookup FindDataSetFiles(const std::string& name) {
  const DataDirSetting setting = DataDirFromSettings(std::nullopt);
  for (const DataFile& file : FindDataSet(name).files) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(setting.dir / file.path, ec)) {
      return {std::nullopt, "data set '" + name + "' not in the data folder '" +
                                setting.dir.string() + "' from " + setting.origin + " (no " +
                                file.path + "; phdslam data fetch " + name + ")"};
    }
  }
  return {setting.dir, ""};
}

}  // namespace phdslam::datasets::testing

/// In a test body or SetUp(): when `lookup` (a DataSetLookup) found nothing, skips the test with
/// its reason, or fails it when DataSetsRequired().
// NOLINTNEXTLINE(cppcoreguidelines-macro-usage): GTEST_SKIP must return from the test itself
#define PHDSLAM_SKIP_WITHOUT_DATA_SET(lookup)                                         \
  do {                                                                                \
    if (!(lookup).dir) {                                                              \
      if (::phdslam::datasets::testing::DataSetsRequired()) {                         \
        GTEST_FAIL() << (lookup).reason << " (required: CI or PHDSLAM_REQUIRE_DATA)"; \
      }                                                                               \
      GTEST_SKIP() << (lookup).reason;                                                \
    }                                                                                 \
  } while (false)
