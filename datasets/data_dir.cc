#include "datasets/data_dir.h"

#include <cstdlib>
#include <stdexcept>
#include <system_error>

namespace phdslam::datasets {

std::filesystem::path ResolveDataDir(const std::optional<std::string>& flag) {
  std::filesystem::path dir;
  std::string origin;
  if (flag.has_value()) {
    dir = *flag;
    origin = "the --data-dir option";
  } else if (const char* env = std::getenv(kDataDirEnvVar); env != nullptr && *env != '\0') {
    dir = env;
    origin = std::string("the environment variable ") + kDataDirEnvVar;
  } else {
    dir = PHDSLAM_DEFAULT_DATA_DIR;
    origin = std::string("the compiled default (PHDSLAM_DEFAULT_DATA_DIR; set ") + kDataDirEnvVar +
             " or pass --data-dir to override)";
  }
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    const bool exists = std::filesystem::exists(dir, ec);
    throw std::runtime_error("data folder '" + dir.string() + "' from " + origin +
                             (exists ? " is not a directory" : " does not exist"));
  }
  return dir;
}

}  // namespace phdslam::datasets
