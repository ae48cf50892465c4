#include "datasets/data_dir.h"

#include <cstdlib>
#include <stdexcept>
#include <system_error>

namespace phdslam::datasets {
namespace {

// The first of `files` that is not a regular file under `dir`; empty when all are.
std::filesystem::path FirstMissing(const std::filesystem::path& dir,
                                   const std::vector<std::filesystem::path>& files) {
  std::error_code ec;
  for (const std::filesystem::path& file : files) {
    if (!std::filesystem::is_regular_file(dir / file, ec)) return file;
  }
  return {};
}

}  // namespace

DataDirSetting DataDirFromSettings(const std::optional<std::string>& flag) {
  if (flag.has_value()) return {*flag, "the --data-dir option"};
  if (const char* env = std::getenv(kDataDirEnvVar); env != nullptr && *env != '\0') {
    return {env, std::string("the environment variable ") + kDataDirEnvVar};
  }
  return {PHDSLAM_DEFAULT_DATA_DIR,
          std::string("the compiled default (PHDSLAM_DEFAULT_DATA_DIR; set ") + kDataDirEnvVar +
              " or pass --data-dir to override)"};
}

std::filesystem::path ResolveDataDir(const std::optional<std::string>& flag) {
  const DataDirSetting setting = DataDirFromSettings(flag);
  std::error_code ec;
  if (!std::filesystem::is_directory(setting.dir, ec)) {
    const bool exists = std::filesystem::exists(setting.dir, ec);
    throw std::runtime_error("data folder '" + setting.dir.string() + "' from " + setting.origin +
                             (exists ? " is not a directory" : " does not exist") +
                             " ('phdslam data fetch NAME' downloads a data set into it, "
                             "'phdslam data check' lists what it holds)");
  }
  return setting.dir;
}

std::filesystem::path BundledDataDir() { return PHDSLAM_BUNDLED_DATA_DIR; }

std::filesystem::path ResolveDataDirFor(const std::optional<std::string>& flag,
                                        const std::vector<std::filesystem::path>& files) {
  const DataDirSetting setting = DataDirFromSettings(flag);
  const std::filesystem::path external_missing = FirstMissing(setting.dir, files);
  if (external_missing.empty()) return setting.dir;
  std::filesystem::path bundled = BundledDataDir();
  const std::filesystem::path bundled_missing = FirstMissing(bundled, files);
  if (bundled_missing.empty()) return bundled;
  throw std::runtime_error("data file '" + external_missing.generic_string() +
                           "' is neither in the data folder '" + setting.dir.string() + "' from " +
                           setting.origin + " nor in the repository's folder '" + bundled.string() +
                           "' (missing there: '" + bundled_missing.generic_string() + "')");
}

}  // namespace phdslam::datasets
