// libFuzzer target: a map CSV file. The reader must accept it or throw std::runtime_error.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "datasets/map_io.h"
#include "fuzz/fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = phdslam::fuzz::ScratchFolder() / "map.csv";
  phdslam::fuzz::WriteInput(path, data, size);
  try {
    (void)phdslam::datasets::ReadMapCsv(path);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
