// The data sets the project reads, file by file: where each file lies in a data folder, its size
// and SHA-256, and where it can be downloaded (docs/guide/data-and-credits.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace phdslam::datasets {

/// One file of a data set.
struct DataFile {
  std::string path;  ///< relative to the data folder, '/'-separated
  std::uintmax_t size = 0;
  std::string sha256;  ///< 64 lower-case hexadecimal digits
  /// Public address of this file alone; empty when it comes from the data set's archive.
  std::string url;
};

/// One data set: its files and its public sources.
struct DataSetEntry {
  std::string name;    ///< as `phdslam data fetch NAME` takes it
  std::string title;   ///< for listings
  std::string folder;  ///< its folder in a data folder
  /// The page to download it from by hand (the manual route).
  std::string home;
  /// Public address of one zip archive holding the files whose url is empty; the archive's own
  /// content is not fixed, each file is verified after extraction.
  std::string archive_url;
  /// Carried in the repository (datasets/data): needs no data folder.
  bool bundled = false;
  std::vector<DataFile> files;
};

/// Every data set, in the order `phdslam data check` lists them: synthetic, victoria-park, mrclam.
const std::vector<DataSetEntry>& DataSetCatalog();

/// The data set called `name`; throws std::invalid_argument listing the known names.
const DataSetEntry& FindDataSet(const std::string& name);

}  // namespace phdslam::datasets
