// Downloads a data set into a data folder, file by file verified against the catalogue: each
// file is written under a temporary name beside its place, checked, and only then moved there.
#pragma once

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>

#include "datasets/data_catalog.h"

namespace phdslam::datasets {

struct FetchReport {
  std::size_t already_verified = 0;  ///< files left as they were
  std::size_t installed = 0;         ///< files downloaded, verified and moved into place
};

/// Fetches the files of `entry` that are not verified in `data_dir` (created when missing).
/// `from` empty: each file from its public address, or from the data set's zip archive
/// (extracted in a temporary folder). `from` a folder, a file:// address or an http(s) address:
/// a mirror laid out as a data folder, each file read from `from`/<path>. A file that fails its
/// size or SHA-256 check is not installed (a corrupt file already in place stays until a verified
/// one replaces it). Every file is tried; then std::runtime_error names each file that failed and
/// why. Progress lines go to `log`.
FetchReport FetchDataSet(const DataSetEntry& entry, const std::filesystem::path& data_dir,
                         const std::string& from, std::ostream& log);

}  // namespace phdslam::datasets
