// Data files loaded once per invocation and shared by every run of a scenario.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>

#include "datasets/mrclam.h"
#include "datasets/paper_synthetic.h"
#include "datasets/victoria_park.h"

namespace phdslam::validation {

/// Data files loaded once and shared by every run of an invocation (keyed by data folder).
/// Thread-safe: concurrent callers wait for one load.
class ScenarioCache {
 public:
  const datasets::PaperSyntheticEnvironment& PaperSynthetic(const std::filesystem::path& data_dir);
  const datasets::VictoriaParkData& VictoriaPark(const std::filesystem::path& data_dir);
  const datasets::MrclamRobotData& Mrclam(const std::filesystem::path& data_dir, int dataset,
                                          int robot);

 private:
  std::mutex mutex_;
  std::map<std::filesystem::path, std::unique_ptr<const datasets::PaperSyntheticEnvironment>>
      paper_synthetic_;
  std::map<std::filesystem::path, std::unique_ptr<const datasets::VictoriaParkData>> victoria_park_;
  std::map<std::tuple<std::filesystem::path, int, int>,
           std::unique_ptr<const datasets::MrclamRobotData>>
      mrclam_;
};

}  // namespace phdslam::validation
