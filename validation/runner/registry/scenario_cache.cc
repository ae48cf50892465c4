#include "validation/runner/registry/scenario_cache.h"

namespace phdslam::validation {

const datasets::PaperSyntheticEnvironment& ScenarioCache::PaperSynthetic(
    const std::filesystem::path& data_dir) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto& slot = paper_synthetic_[data_dir];
  if (!slot) {
    slot = std::make_unique<const datasets::PaperSyntheticEnvironment>(
        datasets::LoadPaperSyntheticEnvironment(data_dir));
  }
  return *slot;
}

const datasets::VictoriaParkData& ScenarioCache::VictoriaPark(
    const std::filesystem::path& data_dir) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto& slot = victoria_park_[data_dir];
  if (!slot) {
    slot = std::make_unique<const datasets::VictoriaParkData>(
        datasets::LoadVictoriaParkData(data_dir));
  }
  return *slot;
}

const datasets::MrclamRobotData& ScenarioCache::Mrclam(const std::filesystem::path& data_dir,
                                                       int dataset, int robot) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto& slot = mrclam_[{data_dir, dataset, robot}];
  if (!slot) {
    slot = std::make_unique<const datasets::MrclamRobotData>(
        datasets::LoadMrclamRobot(data_dir, dataset, robot));
  }
  return *slot;
}

}  // namespace phdslam::validation
