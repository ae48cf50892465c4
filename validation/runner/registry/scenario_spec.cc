#include "validation/runner/registry/scenario_spec.h"

#include "datasets/sha256.h"
#include "datasets/simulation_limits.h"

namespace phdslam::validation {

void RequireStepLimitInRange(int steps) {
  if (steps < 0 || steps > datasets::kMaxSimulatedSteps) {
    throw std::invalid_argument("steps: expected 0 (all) to " +
                                std::to_string(datasets::kMaxSimulatedSteps) + ", got " +
                                std::to_string(steps));
  }
}

nlohmann::json DataFileChecksums(const std::filesystem::path& data_dir,
                                 const std::vector<std::filesystem::path>& files) {
  nlohmann::json out = nlohmann::json::object();
  std::error_code ec;
  for (const std::filesystem::path& file : files) {
    if (!std::filesystem::is_regular_file(data_dir / file, ec)) continue;  // the loader says so
    out[file.generic_string()] = "sha256:" + datasets::FileSha256Hex(data_dir / file);
  }
  return out;
}

}  // namespace phdslam::validation
