// libFuzzer target: the readers of `phdslam ingest`
// (validation/runner/interchange/external_run_reader.h). A generated scenario of a few steps is
// built once, with valid outputs (its true trajectory and map); the first input byte picks one of
// the six files of a seed folder, the rest of the input replaces it. ReadExternalRun must accept
// the folder or throw std::runtime_error.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "datasets/map_io.h"
#include "datasets/scenario_generator.h"
#include "datasets/trajectory_io.h"
#include "fuzz/fuzz_input_file.h"
#include "validation/runner/interchange/external_run_reader.h"

namespace {

namespace d = phdslam::datasets;
namespace v = phdslam::validation;

const d::Scenario& FuzzScenario() {
  static const d::Scenario scenario = [] {
    d::GeneratorOptions o;
    o.steps = 6;
    o.landmarks = 20;
    return d::GenerateScenario(o, 1);
  }();
  return scenario;
}

// Writes the valid trajectory.tum and map.csv of FuzzScenario() into `folder`.
void WriteValidOutputs(const std::filesystem::path& folder) {
  const d::Scenario& s = FuzzScenario();
  std::vector<d::StampedPose> poses;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    poses.push_back({s.StepTime(k), s.truth.poses[k]});
  }
  d::WriteTumTrajectory(folder / v::kExternalTrajectoryFile, poses);
  std::vector<d::MapPoint> map;
  for (const phdslam::Landmark& l : s.truth.landmarks) map.push_back({l, 0.5, std::nullopt});
  d::WriteMapCsv(folder / v::kExternalMapFile, map);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const std::array<const char*, 6> kFiles = {
      v::kExternalTrajectoryFile, v::kExternalMapFile,         v::kExternalPoseCovFile,
      v::kExternalMapsFile,       v::kExternalAssociationFile, v::kExternalTimingFile};
  const std::filesystem::path folder = phdslam::fuzz::ScratchFolder() / "seed-1";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  WriteValidOutputs(folder);
  phdslam::fuzz::WriteInput(folder / kFiles[data[0] % kFiles.size()], data + 1, size - 1);
  try {
    (void)v::ReadExternalRun(folder, FuzzScenario(), "fuzz", 1);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
