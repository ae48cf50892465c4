// libFuzzer target: a MAT-file as Environment_SLAM.mat. The structure check and the loader must
// either accept it or throw std::runtime_error; anything else (a crash, a sanitizer report, another
// exception) is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "datasets/mat_v5_structure.h"
#include "datasets/paper_synthetic.h"
#include "fuzz/fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace ds = phdslam::datasets;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    if (ds::IsMatV5(bytes)) ds::CheckMatV5Structure(bytes, "input");
  } catch (const std::runtime_error&) {
  }
  const auto folder = phdslam::fuzz::ScratchFolder();
  phdslam::fuzz::WriteInput(folder / ds::PaperSyntheticDataFiles().front(), data, size);
  try {
    (void)ds::LoadPaperSyntheticEnvironment(folder);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
