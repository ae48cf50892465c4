// libFuzzer target: an experiment file, read from a file as `phdslam run --experiment` reads it
// (the bounded reader: size, one document, nesting and node caps) and parsed. The reader must
// accept it or throw std::invalid_argument or std::runtime_error naming the file; any other
// exception, or a message without the file's name, is a finding. ci/run-fuzz.sh runs it under
// -rss_limit_mb=2048, so an unbounded read or expansion is a finding too.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "fuzz/fuzz_input_file.h"
#include "validation/runner/experiment/experiment_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path = phdslam::fuzz::ScratchFolder() / "input.yaml";
  phdslam::fuzz::WriteInput(path, data, size);
  try {
    (void)phdslam::validation::ReadExperimentFile(path);
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).find(path.string()) == std::string::npos) std::abort();
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).find(path.string()) == std::string::npos) std::abort();
  }
  return 0;
}
