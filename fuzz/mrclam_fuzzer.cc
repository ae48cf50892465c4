// libFuzzer target: the MRCLAM text files. The first byte chooses the file the rest becomes
// (0 Barcodes.dat, 1 Landmark_Groundtruth.dat, 2 Robot1_Groundtruth.dat, 3 Robot1_Odometry.dat,
// 4 Robot1_Measurement.dat, modulo 5); the others are small valid files. The loader and the
// scenario must accept the data or throw std::runtime_error (std::invalid_argument from the
// scenario for data it cannot use).
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "datasets/mrclam.h"
#include "fuzz/fuzz_input_file.h"

namespace {

struct File {
  const char* name;
  const char* valid;
};

constexpr std::array<File, 5> kFiles = {{
    {"Barcodes.dat", "# h\n1 5\n2 14\n3 41\n4 32\n5 23\n6 61\n7 90\n"},
    {"Landmark_Groundtruth.dat", "# h\n6 2.0 0.0 0.0001 0.0001\n7 0.0 3.0 0.0001 0.0001\n"},
    {"Robot1_Groundtruth.dat", "# h\n99.0 0 0 0\n100.0 0 0 0\n101.0 1 0 0\n102.0 2 0 0.1\n"},
    {"Robot1_Odometry.dat", "# h\n100.0 1.0 0.0\n100.5 1.0 0.1\n101.5 1.0 0.0\n103.0 0 0\n"},
    {"Robot1_Measurement.dat", "# h\n100.5 61 1.5 0.0\n100.5 14 3.0 0.2\n101.2 90 3.0 2.0\n"},
}};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto root = phdslam::fuzz::ScratchFolder();
  const auto folder = root / phdslam::datasets::MrclamFolder(1);
  const std::size_t chosen = data[0] % kFiles.size();
  for (std::size_t i = 0; i < kFiles.size(); ++i) {
    if (i == chosen) {
      phdslam::fuzz::WriteInput(folder / kFiles[i].name, data + 1, size - 1);
    } else {
      const std::string text = kFiles[i].valid;
      phdslam::fuzz::WriteInput(folder / kFiles[i].name,
                                reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
    }
  }
  try {
    const phdslam::datasets::MrclamRobotData robot = phdslam::datasets::LoadMrclamRobot(root, 1, 1);
    phdslam::datasets::MrclamOptions options;
    options.dataset = 1;
    (void)phdslam::datasets::MakeMrclamScenario(robot, 1, options);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
